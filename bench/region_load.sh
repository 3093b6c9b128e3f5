#!/usr/bin/env bash
# What planning a region or view request costs the server (issue 39), under
# wrk: requests/s of GET /stream with a sphere region, with a view, and with
# a view and a screen-space error, against plain uniform /stream requests
# of the same budget, on one mesh. The response cache is off
# (response_cache_bytes: 0) so that every request is planned; the first
# view request with a screen-space error measures the stream's errors
# (meshwave/screen_errors.h) before wrk starts.
#
# Usage: bench/region_load.sh [BUILD_DIR]            (default: build)
# Environment:
#   MESH=FILE         mesh to ingest (default ../shared/data/meshes/feline.ply)
#   BUDGET=N          payload budget in bytes (65536)
#   CONNS=64          wrk connections
#   DURATION=10       seconds per wrk run
#   SERVER_THREADS=2  meshwave-server --threads
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/bench/lib.sh"
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
server_bin=$build/server/meshwave-server
mesh=${MESH:-$root/../shared/data/meshes/feline.ply}
budget=${BUDGET:-65536}
conns=${CONNS:-64}
duration=${DURATION:-10}
server_threads=${SERVER_THREADS:-2}
[[ -x $server_bin ]] || { echo "no meshwave-server at $server_bin (build it first)" >&2; exit 1; }
[[ -r $mesh ]] || { echo "cannot read mesh $mesh" >&2; exit 1; }
for tool in wrk curl jq bc; do
  command -v "$tool" > /dev/null || { echo "$tool not found (bash deploy/install-deps.sh)" >&2; exit 1; }
done

tmp=$(mktemp -d /tmp/region_load.XXXXXX)
server_pid=""
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  if [[ -n $server_pid ]]; then
    kill -TERM "$server_pid" 2> /dev/null || true
    wait "$server_pid" 2> /dev/null || true
  fi
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

echo "ingesting $(basename "$mesh") ..." >&2
"$server_bin" ingest --catalog "$tmp/catalog" "$mesh" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
echo 'response_cache_bytes: 0' > "$tmp/server.conf"
"$server_bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --port-file "$tmp/port" \
  --threads "$server_threads" --config "$tmp/server.conf" --log-level warn > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 200); do [[ -s $tmp/port ]] && break; kill -0 "$server_pid" || break; sleep 0.05; done
[[ -s $tmp/port ]] || { echo "meshwave-server did not start:" >&2; cat "$tmp/server.log" >&2; exit 1; }
S=http://127.0.0.1:$(tr -d '\n' < "$tmp/port")
id=$(curl -sf "$S/v1/meshes" | jq -r '.meshes[0].id')
# A sphere and a camera from the mesh's bounding box.
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave CLI at $cli (build it first)" >&2; exit 1; }
read -r x0 y0 z0 x1 y1 z1 < <("$cli" info "$mesh" --json |
  jq -r '.bbox.min + .bbox.max | map(tostring) | join(" ")')
cx=$(echo "($x0 + $x1) / 2" | bc -l) cy=$(echo "($y0 + $y1) / 2" | bc -l)
cz=$(echo "($z0 + $z1) / 2" | bc -l)
diag=$(echo "sqrt(($x1 - $x0)^2 + ($y1 - $y0)^2 + ($z1 - $z0)^2)" | bc -l)
sphere=$(printf '%.6f,%.6f,%.6f,%.6f' "$x1" "$cy" "$cz" "$(echo "$diag / 5" | bc -l)")
view=$(printf '%.6f,%.6f,%.6f,0,0,-1,45,1280,720' "$cx" "$cy" "$(echo "$cz + 1.5 * $diag" | bc -l)")
base=/v1/meshes/$id/stream
declare -A paths=(
  [uniform]="$base?order=rd&budget=$budget"
  [sphere]="$base?region=$sphere&budget=$budget"
  [view]="$base?view=$view&budget=$budget"
  [view_1px]="$base?view=$view&screen_error=1&budget=$budget"
)
# The first of each: checks it answers, and measures the screen errors.
for kind in uniform sphere view view_1px; do
  start=$(date +%s.%N)
  curl -sf -o "$tmp/$kind.body" "$S${paths[$kind]}" ||
    { echo "$kind: ${paths[$kind]} failed" >&2; exit 1; }
  printf '%s: first request %.0f ms, %s bytes\n' "$kind" \
    "$(echo "($(date +%s.%N) - $start) * 1000" | bc -l)" "$(stat -c %s "$tmp/$kind.body")" >&2
done
echo "# bench/region_load.sh, $(basename "$mesh"), budget $budget, $conns connections, ${duration} s, server threads $server_threads, load $(cut -d' ' -f1 /proc/loadavg); $(date -u +%F)"
echo "| request | requests/s | body bytes | against uniform |"
echo "|---|---:|---:|---:|"
uniform_rps=""
for kind in uniform sphere view view_1px; do
  rps=$(wrk -t2 -c"$conns" -d"${duration}s" "$S${paths[$kind]}" | awk '/Requests\/sec/ { print $2 }')
  [[ -n $uniform_rps ]] || uniform_rps=$rps
  printf '| %s | %.0f | %s | %.2f |\n' "$kind" "$rps" "$(stat -c %s "$tmp/$kind.body")" \
    "$(echo "$rps / $uniform_rps" | bc -l)"
done
