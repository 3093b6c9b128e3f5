#!/usr/bin/env bash
# HTTP serving under load (issue 5): meshwave-server against nginx serving
# the very same bytes as static files, measured with wrk.
#
# Usage: bench/http_load.sh [BUILD_DIR]          (default: build)
#   Expects a built BUILD_DIR/server/meshwave-server; builds nothing.
#   Installs nginx-light, wrk, curl and jq with apt-get when missing (root).
# Environment:
#   MESH=FILE         mesh to ingest (default ../shared/data/meshes/feline.ply,
#                     whose packet 29 is 16218 bytes; igea.ply has none near 16 KiB)
#   TARGET_BYTES=N    pick the packet whose length is closest to N (16384)
#   BUDGET=N          stream budget in bytes (65536)
#   CONNS="64 256"    wrk connection counts
#   DURATION=10       seconds per wrk run (at most 10)
#   WRK_THREADS=2     wrk threads
#   SERVER_THREADS=2  meshwave-server --threads (measure 1, 2 and 4)
#   SERVER_CONF=TEXT  extra server settings in protobuf text format, e.g.
#                     'shared_io_context: true' or 'response_cache_bytes: 0'
#   KEEP=1            keep the temp dir (catalog, docroot, logs, wrk output)
#
# What it does: ingests MESH into a temp catalog, starts meshwave-server on
# 127.0.0.1 (free port, --threads SERVER_THREADS), writes the chosen packet and the
# /stream?order=quality&budget=BUDGET body into a temp docroot, starts nginx
# (worker_processes 2, access_log off, sendfile, keep-alive) on 127.0.0.1
# with its own config/pid/log/temp paths, checks with curl that both serve
# identical bytes, then runs wrk on: server packet, nginx packet, server
# stream, nginx stream file, at each connection count. Prints a Markdown
# table, with each server's CPU time per request (user + system, from
# /proc over the wrk run; nginx's is its workers'). Everything it started is stopped on exit (trap), whatever happens.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/bench/lib.sh"
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
server_bin=$build/server/meshwave-server
mesh=${MESH:-$root/../shared/data/meshes/feline.ply}
target_bytes=${TARGET_BYTES:-16384}
budget=${BUDGET:-65536}
conns_list=${CONNS:-64 256}
duration=${DURATION:-10}
wrk_threads=${WRK_THREADS:-2}
server_threads=${SERVER_THREADS:-2}
server_conf=${SERVER_CONF:-}
(( duration >= 1 && duration <= 10 )) || { echo "DURATION must be 1..10 s" >&2; exit 2; }

[[ -x $server_bin ]] || { echo "no meshwave-server at $server_bin (build it first)" >&2; exit 1; }
[[ -r $mesh ]] || { echo "cannot read mesh $mesh" >&2; exit 1; }

# --- tools -----------------------------------------------------------------
missing=()
command -v nginx > /dev/null || [[ -x /usr/sbin/nginx ]] || missing+=(nginx-light)
command -v wrk > /dev/null || missing+=(wrk)
command -v curl > /dev/null || missing+=(curl)
command -v jq > /dev/null || missing+=(jq)
if (( ${#missing[@]} )); then
  [[ $(id -u) = 0 ]] || { echo "missing ${missing[*]}; run as root or install them" >&2; exit 1; }
  echo "installing ${missing[*]}" >&2
  # Debian images ship a policy-rc.d that keeps nginx's service from starting.
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" >&2 ||
    { apt-get update >&2 &&
      DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" >&2; }
fi
nginx_bin=$(command -v nginx || echo /usr/sbin/nginx)

# --- cleanup ---------------------------------------------------------------
tmp=$(mktemp -d /tmp/http_load.XXXXXX)
server_pid="" nginx_pid=""
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  for pid in $server_pid $nginx_pid; do
    kill -TERM "$pid" 2> /dev/null || true
  done
  for pid in $server_pid $nginx_pid; do
    for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2> /dev/null || true
    wait "$pid" 2> /dev/null || true
  done
  if [[ ${KEEP:-0} = 1 ]]; then echo "kept $tmp" >&2; else rm -rf "$tmp"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# A port nothing listens on (nginx is retried if it loses the race).

# --- catalog and server ----------------------------------------------------
echo "ingesting $(basename "$mesh") ..." >&2
"$server_bin" ingest --catalog "$tmp/catalog" "$mesh" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
conf_args=()
if [[ -n $server_conf ]]; then
  printf '%s\n' "$server_conf" > "$tmp/server.conf"
  conf_args=(--config "$tmp/server.conf")
fi
"$server_bin" --catalog "$tmp/catalog" --listen 127.0.0.1:0 --port-file "$tmp/port" \
  --threads "$server_threads" "${conf_args[@]}" --log-level warn > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 200); do [[ -s $tmp/port ]] && break; kill -0 "$server_pid" || break; sleep 0.05; done
[[ -s $tmp/port ]] || { echo "meshwave-server did not start:" >&2; cat "$tmp/server.log" >&2; exit 1; }
sport=$(tr -d '\n' < "$tmp/port")
S=http://127.0.0.1:$sport

id=$(curl -sf "$S/v1/meshes" | jq -r '.meshes[0].id')
curl -sf "$S/v1/meshes/$id" > "$tmp/details.json"
packets=$(jq -r '.mesh.packets' "$tmp/details.json")
# Every packet's length, fetched over one keep-alive connection.
for (( k = 0; k < packets; ++k )); do
  printf 'url = "%s/v1/meshes/%s/packets/%d"\noutput = "/dev/null"\n' "$S" "$id" "$k"
done > "$tmp/packets.curl"
curl -sf -K "$tmp/packets.curl" -w '%{size_download}\n' > "$tmp/packet_sizes"
best=$(awk -v t="$target_bytes" '{ d = $1 - t; if (d < 0) d = -d;
  if (NR == 1 || d < bd) { bd = d; bk = NR - 1; bl = $1 } } END { print bk, bl }' "$tmp/packet_sizes")
read -r pk plen <<< "$best"
packet_path=/v1/meshes/$id/packets/$pk
stream_path="/v1/meshes/$id/stream?order=quality&budget=$budget"

# --- nginx -------------------------------------------------------------------
docroot=$tmp/docroot
mkdir -p "$docroot" "$tmp/nginx"
curl -sf -o "$docroot/packet.bin" "$S$packet_path"
curl -sf -D "$tmp/stream.headers" -o "$docroot/stream.mwv" "$S$stream_path"
stream_packets=$(awk 'tolower($1) == "x-meshwave-packets:" { print $2 + 0 }' "$tmp/stream.headers")
# Workers run as nobody when started by root: let them read the docroot.
chmod 755 "$tmp" "$docroot"
chmod 644 "$docroot"/*

start_nginx() {
  local port=$1 n=$tmp/nginx
  cat > "$n/nginx.conf" << EOF
worker_processes 2;
pid $n/nginx.pid;
error_log $n/error.log warn;
events { worker_connections 4096; }
http {
  access_log off;
  sendfile on;
  tcp_nopush on;
  tcp_nodelay on;
  keepalive_timeout 65;
  keepalive_requests 100000000;
  default_type application/octet-stream;
  client_body_temp_path $n/client_body;
  proxy_temp_path $n/proxy;
  fastcgi_temp_path $n/fastcgi;
  uwsgi_temp_path $n/uwsgi;
  scgi_temp_path $n/scgi;
  server {
    listen 127.0.0.1:$port;
    root $docroot;
    location / { }
  }
}
EOF
  "$nginx_bin" -p "$n" -e "$n/error.log" -c "$n/nginx.conf" -g 'daemon off;' \
    > "$n/stdout.log" 2>&1 &
  nginx_pid=$!
  for _ in $(seq 100); do
    curl -sf -o /dev/null "http://127.0.0.1:$port/packet.bin" && return 0
    kill -0 "$nginx_pid" 2> /dev/null || break
    sleep 0.05
  done
  kill -TERM "$nginx_pid" 2> /dev/null || true
  wait "$nginx_pid" 2> /dev/null || true
  nginx_pid=""
  return 1
}
nport=""
for _ in 1 2 3 4 5; do
  p=$(free_port)
  if start_nginx "$p"; then nport=$p; break; fi
done
[[ -n $nport ]] || { echo "nginx did not start:" >&2; cat "$tmp/nginx/error.log" >&2; exit 1; }
N=http://127.0.0.1:$nport

# --- same bytes? -------------------------------------------------------------
check_same() {
  local a=$1 b=$2
  curl -sf -o "$tmp/a" "$a"
  curl -sf -o "$tmp/b" "$b"
  cmp -s "$tmp/a" "$tmp/b" || { echo "different bytes: $a vs $b" >&2; exit 1; }
  stat -c %s "$tmp/a"
}
packet_bytes=$(check_same "$S$packet_path" "$N/packet.bin")
stream_bytes=$(check_same "$S$stream_path" "$N/stream.mwv")

# --- wrk ---------------------------------------------------------------------

# cpu_ticks PID...: user + system clock ticks of the processes so far.
cpu_ticks() {
  local pid total=0
  for pid in "$@"; do
    total=$(( total + $(awk '{ print $14 + $15 }' "/proc/$pid/stat" 2> /dev/null || echo 0) ))
  done
  echo "$total"
}
clk_tck=$(getconf CLK_TCK)
nginx_workers=$(pgrep -P "$nginx_pid" | tr '\n' ' ')
cpu=$tmp/cpu.tsv  # name conns microseconds-per-request
: > "$cpu"
# measure NAME URL CONNECTIONS PID...: run_wrk, and the CPU the PIDs used
# per request meanwhile.
measure() {
  local name=$1 url=$2 c=$3
  shift 3
  local before after requests
  before=$(cpu_ticks "$@")
  run_wrk "$name" "$url" "$c"
  after=$(cpu_ticks "$@")
  requests=$(awk '/requests in/ { print $1 }' "$tmp/wrk-$name-$c.txt")
  awk -v n="$name" -v c="$c" -v t=$(( after - before )) -v hz="$clk_tck" -v r="$requests" \
    'BEGIN { us = (r > 0) ? t / hz * 1e6 / r : 0; printf "%s\t%s\t%.1f\n", n, c, us }' >> "$cpu"
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
results=$tmp/results.tsv  # name conns rps p50_ms p99_ms mb_s errors
: > "$results"
for c in $conns_list; do
  measure server-packet "$S$packet_path" "$c" "$server_pid"
  measure nginx-packet "$N/packet.bin" "$c" $nginx_workers
  measure server-stream "$S$stream_path" "$c" "$server_pid"
  measure nginx-stream "$N/stream.mwv" "$c" $nginx_workers
done

# --- report ------------------------------------------------------------------
echo
echo "mesh $(basename "$mesh") (id $id, $packets packets): packet $pk = $packet_bytes bytes" \
  "(closest to $target_bytes); stream order=quality budget=$budget = $stream_bytes bytes" \
  "($stream_packets packets)"
echo "wrk -t$wrk_threads -d${duration}s --latency, connections: $conns_list;" \
  "meshwave-server --threads $server_threads${server_conf:+ ($server_conf)}; nginx $("$nginx_bin" -v 2>&1 | sed 's/.*nginx\///') worker_processes 2;" \
  "$(nproc) cores; load before: $load_before; after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| target | connections | requests/s | p50 ms | p99 ms | transfer MiB/s | errors | CPU µs/req | req/s server/nginx | p99 server/nginx |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
awk -F'\t' '
  FNR == NR { us[$1 "|" $2] = $3; next }
  { key = $1 "|" $2; rps[key] = $3; p99[key] = $5; row[++rows] = $0 }
  END {
    for (i = 1; i <= rows; ++i) {
      split(row[i], f, "\t"); name = f[1]; c = f[2]
      label = name; sub(/-/, " ", label)
      r1 = ""; r2 = ""
      if (name ~ /^server-/) {
        other = name; sub(/^server-/, "nginx-", other); k = other "|" c
        if (rps[k] > 0) r1 = sprintf("%.2f", f[3] / rps[k])
        if (p99[k] > 0) r2 = sprintf("%.2f", f[5] / p99[k])
      }
      printf "| %s | %s | %.0f | %.2f | %.2f | %s | %s | %s | %s | %s |\n",
             label, c, f[3], f[4], f[5], f[6], f[7], us[name "|" c], r1, r2
    }
  }' "$cpu" "$results"
