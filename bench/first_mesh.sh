#!/usr/bin/env bash
# Time to first mesh and decode throughput of the client, over HTTP and
# WebSocket, on loopback.
#
# Usage: bench/first_mesh.sh [BUILD_DIR]        (default: build)
#   Expects BUILD_DIR/server/meshwave-server and BUILD_DIR/bench/first_mesh
#   (configure with -DMESHWAVE_BENCH=ON); builds nothing. With
#   BUILD_DIR/bench/decode_rate it also decodes the ingested container in
#   memory (CPU per payload byte, no network).
# Environment:
#   MESH=FILE   default ../shared/data/meshes/igea.ply, the largest shared mesh
#   RUNS=9      runs per transport (medians reported)
#   PACES="100 250"  WebSocket pacing rates in Mbit/s (issue 19 asks 250)
#   KEEP=1      keep the temp dir
#
# Ingests MESH into a temporary catalog, starts meshwave-server on 127.0.0.1
# (free port, 2 threads), then runs first_mesh RUNS times over http://, over
# ws://, and over ws:// paced by the server at each rate of PACES.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
server_bin=$build/server/meshwave-server
bench_bin=$build/bench/first_mesh
mesh=${MESH:-$root/../shared/data/meshes/igea.ply}
runs=${RUNS:-9}
paces=${PACES:-100 250}
[[ -x $server_bin && -x $bench_bin ]] || { echo "build meshwave-server and first_mesh first" >&2; exit 1; }

tmp=$(mktemp -d /tmp/first_mesh.XXXXXX)
server_pid=""
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  if [[ -n $server_pid ]]; then
    kill -TERM "$server_pid" 2> /dev/null || true
    wait "$server_pid" 2> /dev/null || true
  fi
  if [[ ${KEEP:-0} = 1 ]]; then echo "kept $tmp" >&2; else rm -rf "$tmp"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

"$server_bin" ingest --catalog "$tmp/catalog" "$mesh" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
cat "$tmp/ingest.log"
id=$(awk '/ingested/ {print $1; exit}' "$tmp/ingest.log")
"$server_bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --threads 2 \
  --port-file "$tmp/port" > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 200); do [[ -s $tmp/port ]] && break; sleep 0.05; done
port=$(cat "$tmp/port")
path=127.0.0.1:$port/v1/meshes/$id

uptime
if [[ -x $build/bench/decode_rate ]]; then
  echo "== in memory (decode_rate)"
  "$build/bench/decode_rate" "$(ls "$tmp"/catalog/containers/*.mwv | head -1)" --runs "$runs" | tail -1
fi
echo "== HTTP"
"$bench_bin" "http://$path" --runs "$runs" | tail -1
echo "== WebSocket"
"$bench_bin" "ws://$path" --runs "$runs" | tail -1
for mbit in $paces; do
  echo "== WebSocket paced at $mbit Mbit/s"
  "$bench_bin" "ws://$path" --runs "$runs" --pace $((mbit * 125000)) | tail -1
done
uptime
