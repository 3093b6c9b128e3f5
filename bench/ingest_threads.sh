#!/usr/bin/env bash
# Ingest of one 1 M-triangle mesh on 1 and on 2 threads (issue 19): the
# shared igea.ply subdivided once with Loop by `meshwave subdivide`
# (537,374 vertices, 1,074,744 faces; made afresh each run, the same bytes
# every time), ingested by `meshwave-server ingest --remesh --threads N`
# into an empty catalog: read, clean, remesh, encode, store. --remesh
# because the subdivided mesh is semi-regular and would otherwise be
# encoded as it is. Checks that every run's container is byte for byte the
# first one's, and prints each run's wall time, the best and median per
# thread count, and the ratio of the medians.
#   bench/ingest_threads.sh [BUILD_DIR]        (default build/)
#   RUNS=5 bench/ingest_threads.sh build       runs per thread count (default 3),
#                                              alternating 1, 2, 1, 2, ...
# About 2 minutes at RUNS=3 on two idle cores. MESHWAVE_SHARED_MESHES
# overrides the mesh directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
server=$build/server/meshwave-server
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
runs=${RUNS:-3}
for bin in "$cli" "$server"; do
  [[ -x $bin ]] || { echo "no $bin (build the meshwave and meshwave-server targets)" >&2; exit 1; }
done
[[ -f $meshes/igea.ply ]] || { echo "no igea.ply in $meshes" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time is needed (apt-get install time)" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cli" subdivide "$meshes/igea.ply" "$tmp/igea1.ply" --levels 1 --scheme loop > /dev/null 2>&1
echo "input: $tmp/igea1.ply ($(sha256sum < "$tmp/igea1.ply" | cut -c1-16)...," \
  "$(head -c 400 "$tmp/igea1.ply" | grep -a '^element face' | awk '{print $3}') faces)"
echo "load before: $(uptime)"

# ingest THREADS RUN: "WALL CPU" seconds (CPU = user + system of the
# ingest); the container is kept as $tmp/THREADS-RUN.mwv.
ingest() {
  local catalog=$tmp/catalog-$1-$2
  /usr/bin/time -f '%e %U %S' -o "$tmp/time-$1-$2.txt" \
    "$server" ingest --catalog "$catalog" --remesh --threads "$1" "$tmp/igea1.ply" \
    > "$tmp/out-$1-$2.txt" 2> "$tmp/err-$1-$2.txt" || { cat "$tmp/err-$1-$2.txt" >&2; exit 1; }
  cp "$catalog"/containers/*.mwv "$tmp/$1-$2.mwv"
  rm -rf "$catalog"
  awk '{ printf "%.2f %.2f", $1, $2 + $3 }' "$tmp/time-$1-$2.txt"
}

declare -A times
reference=
for run in $(seq "$runs"); do
  for threads in 1 2; do
    read -r t cpu <<< "$(ingest "$threads" "$run")"
    times[$threads]+="$t "
    if [[ -z $reference ]]; then
      reference=$tmp/$threads-$run.mwv
    elif ! cmp -s "$reference" "$tmp/$threads-$run.mwv"; then
      echo "FAIL: the container of run $run on $threads threads differs from the first" >&2
      exit 1
    fi
    echo "run $run, $threads thread(s): ${t} s wall, ${cpu} s CPU  (id $(grep -o '^[0-9a-f]\{12\} ' "$tmp/out-$threads-$run.txt"))"
  done
done
echo "load after: $(uptime)"
echo "containers: all $((2 * runs)) byte-identical ($(stat -c %s "$reference") bytes," \
  "sha256 $(sha256sum < "$reference" | cut -c1-16)...)"
summary() {  # best and median of the times given
  tr ' ' '\n' | grep . | sort -g | awk '{ t[NR] = $1 } END {
    m = (NR % 2) ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2
    printf "%.2f %.2f", t[1], m }'
}
read -r best1 median1 <<< "$(summary <<< "${times[1]}")"
read -r best2 median2 <<< "$(summary <<< "${times[2]}")"
echo "1 thread:  best ${best1} s, median ${median1} s"
echo "2 threads: best ${best2} s, median ${median2} s"
awk -v a="$median1" -v b="$median2" -v c="$best1" -v d="$best2" \
  'BEGIN { printf "ratio 1 / 2 threads: %.2fx (medians), %.2fx (best)\n", a / b, c / d }'
