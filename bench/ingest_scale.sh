#!/usr/bin/env bash
# Ingest at scale: wall time, CPU time and peak resident memory of
# `meshwave-server ingest` (default settings: fidelity 84, precincts) on
# meshes of 0.1, 1, 4 and 10 M triangles. The meshes are made by
# bench/make_large_mesh from the shared feline.ply (99,732 faces): Loop
# subdivision as often as stays under the count, seeded random edge splits
# up to it, 5 % of the edges flipped and a jitter of 5 % of the mean edge
# length (seed 1), so they are not semi-regular and ingest remeshes them as
# it would a scan; the same bytes every run. Prints a Markdown table and
# the machine's load before and after.
#   bench/ingest_scale.sh [BUILD_DIR]                  (default build-bench/, with
#                                                       -DMESHWAVE_BENCH=ON)
#   SIZES="100000 1000000" bench/ingest_scale.sh ...   other face counts
#   THREADS=2                                           ingest --threads (default 0: all cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
server=$build/server/meshwave-server
maker=$build/bench/make_large_mesh
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
sizes=${SIZES:-100000 1000000 4000000 10000000}
threads=${THREADS:-0}
for bin in "$server" "$maker"; do
  [[ -x $bin ]] || { echo "no $bin (cmake -DMESHWAVE_BENCH=ON, build make_large_mesh and meshwave-server)" >&2; exit 1; }
done
[[ -f $meshes/feline.ply ]] || { echo "no feline.ply in $meshes" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time is needed (apt-get install time)" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "load before: $(uptime)"
echo
echo "| faces | vertices | input MB | wall s | CPU s | peak RSS MiB | container bytes | stream vertices | fidelity reached dB |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for n in $sizes; do
  mesh=$tmp/feline_$n.ply
  made=$("$maker" "$meshes/feline.ply" "$mesh" --faces "$n" --seed 1)
  vertices=$(echo "$made" | sed -E 's/.*: ([0-9]+) vertices.*/\1/')
  faces=$(echo "$made" | sed -E 's/.* ([0-9]+) faces.*/\1/')
  catalog=$tmp/catalog-$n
  /usr/bin/time -f '%e %U %S %M' -o "$tmp/time-$n.txt" \
    "$server" ingest --catalog "$catalog" --threads "$threads" "$mesh" > "$tmp/ingest-$n.txt" 2> "$tmp/ingest-$n.err" ||
    { cat "$tmp/ingest-$n.err" "$tmp/time-$n.txt" >&2; echo "ingest of $n faces failed" >&2; exit 1; }
  read -r wall user sys rss_kb < "$tmp/time-$n.txt"
  line=$(grep -E '^[0-9a-f]{12} ' "$tmp/ingest-$n.txt")
  stream_vertices=$(echo "$line" | sed -E 's/.*\(([0-9]+) vertices.*/\1/')
  bytes=$(echo "$line" | sed -E 's/.* ([0-9]+) bytes\).*/\1/')
  fidelity=$(cat "$tmp/ingest-$n.txt" "$tmp/ingest-$n.err" | grep -oE 'complete stream is at [0-9.]+ dB' |
    grep -oE '[0-9.]+' | head -1 || true)
  printf '| %s | %s | %.1f | %.1f | %.1f | %d | %s | %s | %s |\n' "$faces" "$vertices" \
    "$(echo "$(stat -c %s "$mesh") / 1000000" | bc -l)" "$wall" "$(echo "$user + $sys" | bc -l)" \
    $((rss_kb / 1024)) "$bytes" "$stream_vertices" "${fidelity:--}"
  rm -rf "$catalog" "$mesh"
done
echo
echo "load after: $(uptime)"
