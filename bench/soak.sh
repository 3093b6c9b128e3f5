#!/usr/bin/env bash
# Soak: mixed load on one meshwave-server for a fixed time, sampling its
# resident memory and open descriptors (docs/RELIABILITY.md).
#
# Usage: bench/soak.sh [BUILD_DIR] [SECONDS]     (default: build, 600)
#   Expects BUILD_DIR/server/meshwave-server (and bench/ws_load when the
#   WebSocket load tool exists). Loopback only; everything it starts is
#   stopped on exit. Output: TMP/samples.tsv (t, rss_kib, fds, requests,
#   non-2xx) and a summary on stdout; KEEP=1 keeps TMP; SAVE_SAMPLES=1
#   also writes the samples to bench/soak_samples.tsv (the recorded run).
# Load (all under nice -n 10, so the machine's other users come first):
#   - wrk, 1 thread, 8 connections: a Lua script rotating over packet
#     fetches, /stream prefixes at several budgets, orders and cursors,
#     headers, descriptions, the listing and range requests;
#   - a curl loop opening a fresh connection per request (connection churn);
#   - WS_LOAD (default BUILD_DIR/bench/ws_load, -DMESHWAVE_BENCH=ON; the
#     soak refuses to run without it): WS_SESSIONS (default 16) WebSocket
#     sessions at WS_RATE bytes/s (default 20000), each starting with a
#     4000-byte budget (above both stream headers), refining by 2000 bytes
#     on the same socket until the order is complete, then closing and
#     opening a new session.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
seconds=${2:-600}
server_bin=$build/server/meshwave-server
ws_load=${WS_LOAD:-$build/bench/ws_load}
[[ -x $server_bin ]] || { echo "no $server_bin" >&2; exit 1; }
command -v wrk > /dev/null || { echo "wrk is needed (apt-get install wrk)" >&2; exit 1; }
[[ -x $ws_load ]] || { echo "no $ws_load (configure with -DMESHWAVE_BENCH=ON)" >&2; exit 1; }

tmp=$(mktemp -d /tmp/soak.XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  wait 2> /dev/null || true
  [[ ${KEEP:-0} == 1 ]] && echo "kept $tmp" || rm -rf "$tmp"
}
trap cleanup EXIT

"$server_bin" ingest --catalog "$tmp/catalog" "$root/data/elephant.off" \
  "$root/../shared/data/meshes/holes_patch_sr2.ply" > "$tmp/ingest.log" 2>&1
nice -n 10 "$server_bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --threads 2 \
  --port-file "$tmp/port" > "$tmp/server.log" 2>&1 &
server=$!
pids+=($server)
for _ in $(seq 100); do [[ -s $tmp/port ]] && break; sleep 0.1; done
port=$(cat "$tmp/port")
base=http://127.0.0.1:$port
ids=$(curl -s "$base/v1/meshes" | grep -o '"id": "[0-9a-f]*"' | cut -d'"' -f4 | tr '\n' ' ')
[[ -n $ids ]] || { echo "no meshes listed" >&2; exit 1; }

cat > "$tmp/mixed.lua" <<LUA
local ids = {}
for id in string.gmatch("$ids", "%S+") do ids[#ids + 1] = id end
local paths = {}
for _, id in ipairs(ids) do
  local m = "/v1/meshes/" .. id
  for k = 0, 9 do paths[#paths + 1] = m .. "/packets/" .. k end
  for _, o in ipairs({"quality", "resolution", "rd"}) do
    -- Budgets above every stream header here (a smaller one is a 400 by design).
    for _, b in ipairs({12000, 30000, 200000}) do
      paths[#paths + 1] = m .. "/stream?order=" .. o .. "&budget=" .. b
    end
    paths[#paths + 1] = m .. "/stream?order=" .. o .. "&from=4&budget=5000"
    paths[#paths + 1] = m .. "/stream?order=" .. o .. "&max_level=1"
  end
  paths[#paths + 1] = m .. "/header"
  paths[#paths + 1] = m
  paths[#paths + 1] = m .. "/container"
end
paths[#paths + 1] = "/v1/meshes"
paths[#paths + 1] = "/healthz"
local i = 0
request = function()
  i = i + 1
  local p = paths[(i % #paths) + 1]
  if i % 17 == 0 then
    return wrk.format("GET", "/v1/meshes/" .. ids[1] .. "/container", {["Range"] = "bytes=100-4000"})
  end
  return wrk.format("GET", p)
end
done = function(summary, latency, requests)
  -- errors.status: responses that are not 2xx or 3xx.
  io.write(string.format("wrk_requests %d\nwrk_http_errors %d\nwrk_socket_errors %d\n",
    summary.requests, summary.errors.status, summary.errors.connect + summary.errors.read +
    summary.errors.write + summary.errors.timeout))
end
LUA
nice -n 10 wrk -t1 -c8 -d"${seconds}s" --timeout 10s -s "$tmp/mixed.lua" "$base" > "$tmp/wrk.log" 2>&1 &
pids+=($!)
# Connection churn: a fresh connection per request, checked byte for byte.
first=${ids%% *}
ref=$(curl -s "$base/v1/meshes/$first/stream?budget=6000" | sha256sum)
(
  n=0 bad=0
  end=$((SECONDS + seconds))
  while ((SECONDS < end)); do
    got=$(nice -n 10 curl -s --max-time 10 "$base/v1/meshes/$first/stream?budget=6000" | sha256sum)
    n=$((n + 1)); [[ $got == "$ref" ]] || bad=$((bad + 1))
    sleep 0.05
  done
  echo "churn_requests $n"; echo "churn_errors $bad"
) > "$tmp/churn.log" 2>&1 &
pids+=($!)
# WebSocket sessions with refine, on each mesh in turn (ws_load holds them
# for the soak's time minus its ramp).
ws_pids=()
for id in $ids; do
  nice -n 10 "$ws_load" --port "$port" --mesh "$id" --sessions $((${WS_SESSIONS:-16} / 2)) \
    --rate "${WS_RATE:-20000}" --seconds $((seconds - 2)) --ramp-per-second 100 \
    --budget 4000 --refine 2000 > "$tmp/ws_$id.log" 2>&1 &
  ws_pids+=($!)
  pids+=($!)
done

printf 't_s\trss_kib\tfds\trequests_total\n' > "$tmp/samples.tsv"
start=$SECONDS
while ((SECONDS - start < seconds)); do
  kill -0 $server 2> /dev/null || { echo "the server died" >&2; cat "$tmp/server.log" >&2; exit 1; }
  rss=$(awk '/^VmRSS/ {print $2}' /proc/$server/status)
  fds=$(ls /proc/$server/fd | wc -l)
  reqs=$(curl -s --max-time 5 "$base/metrics" |
         awk '/^meshwave_http_requests_total/ {s += $2} END {printf "%d", s}')
  printf '%d\t%s\t%s\t%s\n' $((SECONDS - start)) "$rss" "$fds" "$reqs" >> "$tmp/samples.tsv"
  sleep 10
done
wait "${pids[1]}" || true  # wrk
sleep 1
wait "${pids[2]}" || true  # churn loop
ws_rc=0
for p in "${ws_pids[@]}"; do wait "$p" || ws_rc=1; done
cat "$tmp/samples.tsv"
cat "$tmp/wrk.log" | grep -E "^wrk_|Requests/sec|Latency" || cat "$tmp/wrk.log"
cat "$tmp/churn.log"
for f in "$tmp"/ws_*.log; do echo "== $(basename "$f")"; cat "$f"; done
awk '/^ws_/ {s[$1] += $2} END {for (k in s) print k, s[k]}' "$tmp"/ws_*.log | sort
echo "ws_load exit: $ws_rc (0: every session connected, none failed)"
# Memory after warm-up (the first minute): min, max, last, and the spread.
awk -F'\t' 'NR > 1 && $1 >= 60 {if (!n++) {min = max = $2}; if ($2 < min) min = $2;
  if ($2 > max) max = $2; last = $2; fmin = (n == 1 || $3 < fmin) ? $3 : fmin;
  fmax = ($3 > fmax) ? $3 : fmax}
  END {printf "rss_after_warmup_kib min %d max %d last %d spread %.1f%%\nfds_after_warmup min %d max %d\n",
    min, max, last, 100 * (max - min) / min, fmin, fmax}' "$tmp/samples.tsv"
echo "server log lines with error: $(grep -ci error "$tmp/server.log" || true)"
# The recorded samples (bench/soak_samples.tsv, what docs/RELIABILITY.md
# cites) are replaced only when asked: SAVE_SAMPLES=1.
if [[ ${SAVE_SAMPLES:-0} == 1 ]]; then
  cp "$tmp/samples.tsv" "$root/bench/soak_samples.tsv"
  echo "samples written to bench/soak_samples.tsv"
fi
