#!/usr/bin/env bash
# Two builds of meshwave side by side, in one run: are their streams the same
# bytes, and are they as fast? For a refactoring that must change nothing a
# user sees (the same containers, decoded meshes and served bytes) and must
# cost nothing (encode, decode and serving times within noise).
#
# Usage: bench/compare_builds.sh OLD_BUILD NEW_BUILD
#   Each BUILD holds tools/meshwave/meshwave and server/meshwave-server, e.g.
#     git worktree add /tmp/old COMMIT && cmake -S /tmp/old -B /tmp/old/build \
#       -G Ninja -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/old/build \
#       -j2 --target meshwave meshwave-server
# Environment:
#   MESHES="A B"   meshes to compare (default: the shipped data/elephant.off
#                  and the shared bunny, feline, igea and fandisk when present)
#   RUNS=3         timed runs per binary and step (alternating old, new)
#   DURATION=5     seconds per wrk run; CONNS=64 wrk connections
#   FORMAT_BUMP=1  the new build writes a newer format version: containers
#                  and served bodies may differ in that one byte (same
#                  size, at most one differing byte: the version field);
#                  each build decodes its own container; the two catalogs'
#                  entries are matched by name (ids hash the version)
#
# Same bytes: each mesh is encoded by both CLIs (containers compared); the
# new container is decoded by both CLIs at 25 % and 100 % of its bytes in the
# quality, resolution and rd orders (meshes compared); both servers ingest
# every mesh into catalogs of their own and answer /stream in the three
# orders at three budgets and every tenth packet (bodies compared). Any
# difference fails the run. Speeds: medians of alternating runs, RUNS of the
# encode (wall), 5 x RUNS of the complete decode (the decoder's time as
# `decode --json` reports it), RUNS of wrk on a packet and on a /stream URL.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/bench/lib.sh"
[[ $# == 2 ]] || { sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
old=$(cd "$1" && pwd) new=$(cd "$2" && pwd)
runs=${RUNS:-3} duration=${DURATION:-5} conns=${CONNS:-64} wrk_threads=2
need_tools curl jq wrk sha256sum
for b in "$old" "$new"; do
  for bin in tools/meshwave/meshwave server/meshwave-server; do
    [[ -x $b/$bin ]] || { echo "no $b/$bin (build the meshwave and meshwave-server targets)" >&2; exit 1; }
  done
done
if [[ -n ${MESHES:-} ]]; then
  read -r -a meshes <<< "$MESHES"
else
  meshes=("$root/data/elephant.off")
  shared=$root/../shared/data/meshes
  for m in bunny_stanford_zipper.ply feline.ply igea.ply fandisk.obj; do
    [[ -f $shared/$m ]] && meshes+=("$shared/$m")
  done
fi

tmp=$(mktemp -d /tmp/compare_builds.XXXXXX)
pids=()
cleanup() {
  local rc=$?
  trap - EXIT
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2> /dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2> /dev/null || true; done
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT

# seconds CMD...: wall seconds of one run (output discarded, failure fatal).
seconds() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" > /dev/null 2>> "$tmp/errors.log" || { cat "$tmp/errors.log" >&2; echo "failed: $*" >&2; exit 1; }
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}
median() { sort -g | awk '{ v[NR] = $1 } END { printf "%.3f", (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
bump=${FORMAT_BUMP:-0}
same() {  # same LABEL FILE_A FILE_B
  if ! cmp -s "$2" "$3"; then
    # A newer format version: the same size and only the version byte.
    local differing
    differing=$(cmp -l "$2" "$3" 2> /dev/null | wc -l || true)
    if [[ $bump != 1 || $(stat -c %s "$2") != $(stat -c %s "$3") || $differing -gt 1 ]]; then
      echo "DIFFERENT: $1 ($2 vs $3)" >&2
      exit 1
    fi
    version_only=$((version_only + 1))
  fi
  checked=$((checked + 1))
}
checked=0 version_only=0

echo "# old $old, new $new; $(date -u '+%Y-%m-%d %H:%M UTC'); load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| mesh | container bytes | encode s old | encode s new | new/old | decode ms old | decode ms new | new/old |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
for mesh in "${meshes[@]}"; do
  name=$(basename "${mesh%.*}")
  : > "$tmp/enc-old" && : > "$tmp/enc-new" && : > "$tmp/dec-old" && : > "$tmp/dec-new"
  for (( r = 0; r < runs; ++r )); do
    for side in old new; do
      b=${!side}
      seconds "$b/tools/meshwave/meshwave" encode "$mesh" "$tmp/$name.$side.mwv" >> "$tmp/enc-$side"
    done
  done
  same "$name container" "$tmp/$name.old.mwv" "$tmp/$name.new.mwv"
  size=$(stat -c %s "$tmp/$name.new.mwv")
  for order in quality resolution rd; do
    for budget in $((size / 4)) "$size"; do
      for side in old new; do
        b=${!side}
        container=$tmp/$name.new.mwv
        [[ $bump == 1 ]] && container=$tmp/$name.$side.mwv
        "$b/tools/meshwave/meshwave" decode --order "$order" --budget "$budget" \
          "$container" "$tmp/$name.$side.ply" > /dev/null 2>> "$tmp/errors.log"
      done
      same "$name decoded ($order, $budget bytes)" "$tmp/$name.old.ply" "$tmp/$name.new.ply"
    done
  done
  # The decoder's own time (decode --json: decode_ms, without process start
  # and file writing), five times as many runs: it is short.
  for (( r = 0; r < 5 * runs; ++r )); do
    for side in old new; do
      b=${!side}
      container=$tmp/$name.new.mwv
      [[ $bump == 1 ]] && container=$tmp/$name.$side.mwv
      "$b/tools/meshwave/meshwave" decode --json "$container" "$tmp/$name.$side.ply" \
        2>> "$tmp/errors.log" | jq -r .decode_ms >> "$tmp/dec-$side"
    done
  done
  eo=$(median < "$tmp/enc-old") en=$(median < "$tmp/enc-new")
  do_=$(median < "$tmp/dec-old") dn=$(median < "$tmp/dec-new")
  printf '| %s | %s | %s | %s | %.3f | %s | %s | %.3f |\n' "$name" "$size" "$eo" "$en" \
    "$(echo "$en / $eo" | bc -l)" "$do_" "$dn" "$(echo "$dn / $do_" | bc -l)"
done

# --- servers ------------------------------------------------------------------
start_server() {  # start_server SIDE -> sets port_SIDE
  local side=$1 b=${!1}
  "$b/server/meshwave-server" ingest --catalog "$tmp/catalog-$side" "${meshes[@]}" \
    > "$tmp/ingest-$side.log" 2>&1 || { cat "$tmp/ingest-$side.log" >&2; exit 1; }
  "$b/server/meshwave-server" --catalog "$tmp/catalog-$side" --listen 127.0.0.1:0 \
    --port-file "$tmp/port-$side" --log-level warn > "$tmp/server-$side.log" 2>&1 &
  pids+=($!)
  for _ in $(seq 200); do [[ -s $tmp/port-$side ]] && break; sleep 0.05; done
  [[ -s $tmp/port-$side ]] || { echo "$side server did not start:" >&2; cat "$tmp/server-$side.log" >&2; exit 1; }
  printf -v "port_$side" '%s' "$(tr -d '\n' < "$tmp/port-$side")"
}
start_server old
start_server new
O=http://127.0.0.1:$port_old N=http://127.0.0.1:$port_new
# Entries as "name id", by name: equal ids unless the format changed.
curl -sf "$O/v1/meshes?limit=100" | jq -r '.meshes[] | "\(.name) \(.id)"' | sort > "$tmp/ids-old"
curl -sf "$N/v1/meshes?limit=100" | jq -r '.meshes[] | "\(.name) \(.id)"' | sort > "$tmp/ids-new"
if [[ $bump == 1 ]]; then
  cut -d' ' -f1 "$tmp/ids-old" > "$tmp/names-old" && cut -d' ' -f1 "$tmp/ids-new" > "$tmp/names-new"
  same "catalog names" "$tmp/names-old" "$tmp/names-new"
else
  same "catalog ids" "$tmp/ids-old" "$tmp/ids-new"
fi
fetch_same() {  # fetch_same OLD_PATH NEW_PATH
  curl -sf -o "$tmp/body-old" "$O$1" || { echo "old server failed on $1" >&2; exit 1; }
  curl -sf -o "$tmp/body-new" "$N$2" || { echo "new server failed on $2" >&2; exit 1; }
  same "served $2" "$tmp/body-old" "$tmp/body-new"
}
paste -d' ' "$tmp/ids-old" "$tmp/ids-new" > "$tmp/pairs"
while read -r _ old_id _ id; do
  packets=$(curl -sf "$N/v1/meshes/$id" | jq -r '.mesh.packets')
  for order in quality resolution rd; do
    for budget in 4000 40000 1000000000; do
      q="stream?order=$order&budget=$budget"
      fetch_same "/v1/meshes/$old_id/$q" "/v1/meshes/$id/$q"
    done
  done
  for (( k = 0; k < packets; k += 10 )); do
    fetch_same "/v1/meshes/$old_id/packets/$k" "/v1/meshes/$id/packets/$k"
  done
done < "$tmp/pairs"
echo
if [[ $version_only -gt 0 ]]; then
  echo "Same bytes: $checked comparisons (containers, decoded meshes, served streams and packets):" \
    "$((checked - version_only)) identical, $version_only differing in the format version byte only."
else
  echo "Same bytes: $checked comparisons (containers, decoded meshes, served streams and packets), all identical."
fi

old_id=$(head -1 "$tmp/pairs" | cut -d' ' -f2) id=$(head -1 "$tmp/pairs" | cut -d' ' -f4)
echo
echo "| wrk -c$conns ${duration}s | req/s old | req/s new | new/old |"
echo "|---|---:|---:|---:|"
for what in packet stream; do
  [[ $what == packet ]] && path="/packets/1" || path="/stream?order=quality&budget=65536"
  : > "$tmp/rps-old" && : > "$tmp/rps-new"
  for (( r = 0; r < runs; ++r )); do
    for side in old new; do
      [[ $side == old ]] && base=$O/v1/meshes/$old_id || base=$N/v1/meshes/$id
      wrk -t"$wrk_threads" -c"$conns" -d"${duration}s" "$base$path" > "$tmp/wrk.txt" 2>&1
      grep -q "Non-2xx\|Socket errors" "$tmp/wrk.txt" && { cat "$tmp/wrk.txt" >&2; exit 1; }
      awk '/^Requests\/sec:/ { print $2 }' "$tmp/wrk.txt" >> "$tmp/rps-$side"
    done
  done
  ro=$(median < "$tmp/rps-old") rn=$(median < "$tmp/rps-new")
  printf '| %s | %.0f | %.0f | %.3f |\n' "$what" "$ro" "$rn" "$(echo "$rn / $ro" | bc -l)"
done
echo
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
