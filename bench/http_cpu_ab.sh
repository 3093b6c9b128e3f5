#!/usr/bin/env bash
# Server CPU per request, A/B (issue 19): meshwave-server variants in turn
# against the same catalog, each under one wrk run, ROUNDS times
# interleaved, so that the other load of a shared machine falls on all of
# them alike. Prints name, requests/s, server CPU (user + system, from
# /proc) in microseconds per request, and the 1-minute load average.
#
# Usage: bench/http_cpu_ab.sh NAME=BINARY[@CONFIG_TEXT] ...
#   e.g. bench/http_cpu_ab.sh before=/tmp/base/build/server/meshwave-server \
#          after=build/server/meshwave-server \
#          shared=build/server/meshwave-server@'shared_io_context: true'
# Environment: MESH (feline.ply), TARGET=packet|stream (packet: packet 29,
#   16,218 bytes; stream: /stream?order=quality&budget=65536), THREADS=2,
#   CONNS=64, ROUNDS=3, DURATION=5 (seconds per run, at most 10).
# Needs wrk and curl (bench/http_load.sh installs them).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mesh=${MESH:-$root/../shared/data/meshes/feline.ply}
target=${TARGET:-packet}
threads=${THREADS:-2}
conns=${CONNS:-64}
rounds=${ROUNDS:-3}
duration=${DURATION:-5}
(( duration >= 1 && duration <= 10 )) || { echo "DURATION must be 1..10 s" >&2; exit 2; }
(( $# > 0 )) || { echo "usage: $0 NAME=BINARY[@CONFIG_TEXT] ..." >&2; exit 2; }
tmp=$(mktemp -d /tmp/http_cpu_ab.XXXXXX)
pid=""
cleanup() {
  [[ -n $pid ]] && { kill -TERM "$pid" 2> /dev/null || true; wait "$pid" 2> /dev/null || true; }
  rm -rf "$tmp"
}
trap cleanup EXIT
first=${1#*=}
first=${first%%@*}
"$first" ingest --catalog "$tmp/catalog" "$mesh" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
id=$(awk '{ print $1; exit }' "$tmp/ingest.log")
case $target in
  packet) path=/v1/meshes/$id/packets/29 ;;
  stream) path="/v1/meshes/$id/stream?order=quality&budget=65536" ;;
  *) echo "TARGET must be packet or stream" >&2; exit 2 ;;
esac
hz=$(getconf CLK_TCK)
run() {
  local name=$1 bin=$2 conf=$3 args=()
  rm -f "$tmp/port"
  if [[ -n $conf ]]; then printf '%s\n' "$conf" > "$tmp/conf"; args=(--config "$tmp/conf"); fi
  "$bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --port-file "$tmp/port" \
    --threads "$threads" "${args[@]}" --log-level warn > "$tmp/server.log" 2>&1 &
  pid=$!
  for _ in $(seq 100); do [[ -s $tmp/port ]] && break; sleep 0.05; done
  local url="http://127.0.0.1:$(tr -d '\n' < "$tmp/port")$path"
  curl -sf -o /dev/null "$url"
  local before after
  before=$(awk '{ print $14 + $15 }' "/proc/$pid/stat")
  wrk -t2 -c"$conns" -d"${duration}s" "$url" > "$tmp/wrk.txt" 2>&1
  after=$(awk '{ print $14 + $15 }' "/proc/$pid/stat")
  kill -TERM "$pid"; wait "$pid" || true; pid=""
  awk -v name="$name" -v t=$(( after - before )) -v hz="$hz" -v load="$(cut -d' ' -f1 /proc/loadavg)" \
    '/requests in/ { n = $1 } /Requests\/sec/ { rps = $2 }
     END { us = (n > 0) ? t / hz * 1e6 / n : 0; printf "%s\t%.0f\t%.1f\t%s\n", name, rps, us, load }' \
    "$tmp/wrk.txt"
}
echo "target $target ($path), --threads $threads, wrk -t2 -c$conns -d${duration}s, $rounds rounds"
printf 'name\treq/s\tCPU us/req\tload\n'
for _ in $(seq "$rounds"); do
  for spec in "$@"; do
    name=${spec%%=*}
    rest=${spec#*=}
    bin=${rest%%@*}
    conf=""
    [[ $rest == *@* ]] && conf=${rest#*@}
    run "$name" "$bin" "$conf"
  done
done
