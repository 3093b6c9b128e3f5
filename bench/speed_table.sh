#!/usr/bin/env bash
# Every figure of issue 19 in one run, each beside what a user would use
# instead: meshwave-server against nginx serving the same bytes (packet and
# /stream, 64 and 256 connections: req/s and p99 ratios), the client's CPU
# per payload byte in memory and over HTTP and WebSocket, time to first
# mesh, the lag behind WebSocket delivery paced at 100 and 250 Mbit/s, and
# the ingest of a 1 M-triangle mesh on one and on two threads.
#
# Usage: bench/speed_table.sh [BUILD_DIR]     (default: build-bench)
#   BUILD_DIR must hold meshwave-server, meshwave, bench/first_mesh and
#   bench/decode_rate: configure with the bench preset
#     cmake --preset bench && cmake --build build-bench -j2 \
#       --target meshwave-server meshwave first_mesh decode_rate
# Environment: passed on to the three scripts (MESH is not: each uses its
# own default, the meshes the issue names). SKIP_INGEST=1 leaves out the
# ingest (about 2 minutes at its default RUNS=3 on idle cores).
# Run it on a quiet machine: every figure here is a time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
[[ $build = /* ]] || build=$PWD/$build
unset MESH

echo "# issue 19 figures, $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git -C "$root" rev-parse --short HEAD)"
echo "start: $(uptime)"
echo
echo "## Serving: meshwave-server against nginx (bench/http_load.sh)"
"$root/bench/http_load.sh" "$build"
echo
echo "## Client: in memory, HTTP, WebSocket, paced (bench/first_mesh.sh, igea)"
PACES=${PACES:-100 250} "$root/bench/first_mesh.sh" "$build"
if [[ ${SKIP_INGEST:-0} != 1 ]]; then
  echo
  echo "## Ingest of a 1 M-triangle mesh on 1 and 2 threads (bench/ingest_threads.sh)"
  "$root/bench/ingest_threads.sh" "$build"
fi
echo
echo "end: $(uptime)"
