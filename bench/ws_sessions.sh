#!/usr/bin/env bash
# WebSocket sessions under load: N concurrent paced sessions held on one
# meshwave-server for a while, the server's memory sampled throughout.
#
# Usage: bench/ws_sessions.sh [BUILD_DIR]        (default: build)
#   Expects BUILD_DIR/server/meshwave-server and BUILD_DIR/bench/ws_load
#   (configure with -DMESHWAVE_BENCH=ON); builds nothing.
# Environment:
#   MESH=FILE      mesh to ingest and stream (default
#                  ../shared/data/meshes/elephant_subdiv2.ply, 81 kB stream)
#   SESSIONS=2000  concurrent sessions
#   RATE=8000      bytes per second each session asks for
#   SECONDS_HELD=60
#   THREADS=2      server io threads
#   KEEP=1         keep the temp dir (catalog, logs, samples)
#
# What it does: raises `ulimit -n` (each session is a descriptor on both
# sides), ingests MESH into a temporary catalog, starts meshwave-server on
# 127.0.0.1 (free port), samples its VmRSS from /proc/PID/status every
# second, and runs ws_load: SESSIONS sessions started at 1000 per second,
# each streaming MESH at RATE bytes/s over and over, held SECONDS_HELD
# seconds. Prints ws_load's report, the RSS before, peak and at the end,
# and the server's WebSocket gauge during the hold. Everything it started
# is stopped on exit.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
server_bin=$build/server/meshwave-server
load_bin=$build/bench/ws_load
mesh=${MESH:-$root/../shared/data/meshes/elephant_subdiv2.ply}
sessions=${SESSIONS:-2000}
rate=${RATE:-8000}
held=${SECONDS_HELD:-60}
threads=${THREADS:-2}
[[ -x $server_bin ]] || { echo "no meshwave-server at $server_bin" >&2; exit 1; }
[[ -x $load_bin ]] || { echo "no ws_load at $load_bin (-DMESHWAVE_BENCH=ON)" >&2; exit 1; }
[[ -r $mesh ]] || { echo "cannot read mesh $mesh" >&2; exit 1; }

# Server and load tool each hold one descriptor per session.
want=$((2 * sessions + 256))
if (( $(ulimit -n) < want )); then
  ulimit -n "$want" 2> /dev/null || ulimit -n "$(ulimit -Hn)"
fi
(( $(ulimit -n) >= sessions + 64 )) || { echo "ulimit -n $(ulimit -n) is too low" >&2; exit 1; }

tmp=$(mktemp -d /tmp/ws_sessions.XXXXXX)
server_pid="" sampler_pid=""
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  [[ -n $sampler_pid ]] && kill "$sampler_pid" 2> /dev/null || true
  if [[ -n $server_pid ]]; then
    kill -TERM "$server_pid" 2> /dev/null || true
    for _ in $(seq 100); do kill -0 "$server_pid" 2> /dev/null || break; sleep 0.1; done
    kill -KILL "$server_pid" 2> /dev/null || true
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
id=$(awk '/ingested/ {print $1; exit}' "$tmp/ingest.log")
[[ -n $id ]] || { cat "$tmp/ingest.log" >&2; exit 1; }

"$server_bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --threads "$threads" \
  --port-file "$tmp/port" > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 200); do [[ -s $tmp/port ]] && break; sleep 0.05; done
port=$(cat "$tmp/port")

rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$server_pid/status"; }
rss_before=$(rss_kib)
( while kill -0 "$server_pid" 2> /dev/null; do
    echo "$(date +%s) $(rss_kib)"
    sleep 1
  done ) > "$tmp/rss.tsv" &
sampler_pid=$!
# The gauge halfway through the hold (ramp about SESSIONS/1000 + 1 s).
( sleep $(( sessions / 1000 + 1 + held / 2 ))
  exec 3<> "/dev/tcp/127.0.0.1/$port"
  printf 'GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n' >&3
  grep '^meshwave_websocket_connections' <&3 > "$tmp/gauge" || true ) &

echo "meshwave-server (pid $server_pid, $threads threads) on port $port, mesh $id ($(basename "$mesh"))"
echo "ulimit -n $(ulimit -n); $sessions sessions at $rate B/s for $held s"
status=0
"$load_bin" --port "$port" --mesh "$id" --sessions "$sessions" --rate "$rate" \
  --seconds "$held" || status=$?
sleep 1
rss_end=$(rss_kib)
kill "$sampler_pid" 2> /dev/null || true
sampler_pid=""
peak=$(awk 'BEGIN {m = 0} $2 > m {m = $2} END {print m}' "$tmp/rss.tsv")
echo "server RSS: before $((rss_before / 1024)) MiB, peak $((peak / 1024)) MiB, after the sessions closed $((rss_end / 1024)) MiB"
echo "during the hold: $(cat "$tmp/gauge" 2> /dev/null || echo 'gauge not read')"
echo "server log: $(grep -c ' open$' "$tmp/server.log") sessions opened, $(grep -c ' closed after' "$tmp/server.log") closed"
exit "$status"
