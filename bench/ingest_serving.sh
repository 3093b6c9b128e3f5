#!/usr/bin/env bash
# Serving while an upload is ingested: wrk's packet rate against a
# meshwave-server that is idle, then while it ingests an uploaded
# 1 M-triangle mesh (POST /v1/meshes: its upload worker process, niced), then
# idle again, all in one run. The issue's target: during >= 0.8x idle.
#
# Usage: bench/ingest_serving.sh [BUILD_DIR]   (default build-bench/, with
#   -DMESHWAVE_BENCH=ON; needs server/meshwave-server and bench/make_large_mesh)
# Environment:
#   FACES=1000000   triangles of the uploaded mesh (bench/make_large_mesh from
#                   the shared feline.ply, seed 1: irregular, so it is remeshed)
#   DURATION=20     seconds of each wrk run; CONNS=64 wrk connections
#   KEEP=1          keep the temp dir (catalog, logs, wrk output)
# The wrk run during the ingest starts once the worker process is up and must
# end before it does (else the run fails: raise FACES); the ingest's wall
# time under load is printed too.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/bench/lib.sh"
build=${1:-$root/build-bench}
[[ $build = /* ]] || build=$PWD/$build
server_bin=$build/server/meshwave-server maker=$build/bench/make_large_mesh
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
faces=${FACES:-1000000} duration=${DURATION:-20} conns=${CONNS:-64} wrk_threads=2
need_tools curl jq wrk
for bin in "$server_bin" "$maker"; do
  [[ -x $bin ]] || { echo "no $bin (cmake -DMESHWAVE_BENCH=ON, build make_large_mesh and meshwave-server)" >&2; exit 1; }
done
[[ -f $meshes/feline.ply ]] || { echo "no feline.ply in $meshes" >&2; exit 1; }

tmp=$(mktemp -d /tmp/ingest_serving.XXXXXX)
server_pid="" upload_pid=""
cleanup() {
  local rc=$?
  trap - EXIT
  for pid in $upload_pid $server_pid; do kill -TERM "$pid" 2> /dev/null || true; done
  for pid in $upload_pid $server_pid; do wait "$pid" 2> /dev/null || true; done
  if [[ ${KEEP:-0} = 1 ]]; then echo "kept $tmp" >&2; else rm -rf "$tmp"; fi
  exit "$rc"
}
trap cleanup EXIT

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git -C "$root" rev-parse --short HEAD); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$maker" "$meshes/feline.ply" "$tmp/upload.ply" --faces "$faces" --seed 1 > "$tmp/made.txt"
"$server_bin" ingest --catalog "$tmp/catalog" "$meshes/feline.ply" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
token=bench-$RANDOM$RANDOM
printf 'upload_token: "%s"\nupload_limit_bytes: 268435456\n' "$token" > "$tmp/server.conf"
"$server_bin" --catalog "$tmp/catalog" --config "$tmp/server.conf" --listen 127.0.0.1:0 \
  --port-file "$tmp/port" --log-level warn > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 200); do [[ -s $tmp/port ]] && break; sleep 0.05; done
[[ -s $tmp/port ]] || { echo "meshwave-server did not start:" >&2; cat "$tmp/server.log" >&2; exit 1; }
S=http://127.0.0.1:$(tr -d '\n' < "$tmp/port")
id=$(curl -sf "$S/v1/meshes" | jq -r '.meshes[0].id')
url=$S/v1/meshes/$id/packets/1

results=$tmp/results.tsv
run() {  # run NAME: one wrk run, "NAME rps p99_ms errors" appended to $results
  local out=$tmp/wrk-$1.txt
  wrk -t"$wrk_threads" -c"$conns" -d"${duration}s" --timeout 5s --latency "$url" > "$out" 2>&1
  local errs
  errs=$(awk '/Non-2xx/ { n += $NF } /Socket errors/ { gsub(/,/, ""); n += $4 + $6 + $8 + $10 } END { print n + 0 }' "$out")
  printf '%s\t%s\t%s\t%s\n' "$1" "$(awk '/^Requests\/sec:/ { print $2 }' "$out")" \
    "$(to_ms "$(awk '$1 == "99%" { print $2 }' "$out")")" "$errs" >> "$results"
}
worker_running() { pgrep -f -- "meshwave-server ingest-upload" > /dev/null; }

wrk -t"$wrk_threads" -c"$conns" -d2s "$url" > /dev/null  # warm-up
run idle
upload_start=$SECONDS
curl -s -o "$tmp/upload.json" -w '%{http_code}' -H "Authorization: Bearer $token" \
  --data-binary "@$tmp/upload.ply" "$S/v1/meshes?name=large&format=ply" > "$tmp/upload.code" &
upload_pid=$!
for _ in $(seq 600); do worker_running && break; sleep 0.1; done
worker_running || { echo "the upload worker did not start" >&2; cat "$tmp/server.log" >&2; exit 1; }
run during
worker_running || { echo "the ingest ended before the wrk run did: raise FACES" >&2; exit 1; }
wait "$upload_pid"; upload_pid=""
ingest_seconds=$((SECONDS - upload_start))
[[ $(cat "$tmp/upload.code") == 201 ]] || { echo "upload failed: $(cat "$tmp/upload.code") $(cat "$tmp/upload.json")" >&2; exit 1; }
run idle_after

echo
echo "| wrk -c$conns ${duration}s, packet 1 of feline | req/s | p99 ms | errors |"
echo "|---|---:|---:|---:|"
awk -F'\t' '{ printf "| %s | %.0f | %s | %s |\n", $1, $2, $3, $4 }' "$results"
awk -F'\t' '{ r[$1] = $2 } END { printf "\nduring / idle (mean of before and after): %.3f\n", r["during"] / ((r["idle"] + r["idle_after"]) / 2) }' "$results"
echo "upload of $(cat "$tmp/made.txt" | sed -E 's/.*: //') ($(stat -c %s "$tmp/upload.ply") bytes) ingested in ${ingest_seconds} s under load: $(jq -c '{id, vertices, bytes}' "$tmp/upload.json" 2> /dev/null || cat "$tmp/upload.json")"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
