#!/usr/bin/env bash
# HTTP load through the scaled-out deployment (docs/DEPLOY.md): the
# load test of bench/http_load.sh (same mesh, same packet, same stream)
# rerun against a replica directly and through nginx, with PostgreSQL as
# the catalog, two meshwave-server replicas sharing a store, and nginx
# with deploy/nginx/meshwave-locations.conf in front (cached: HIT; and
# with the cache bypassed for the request, which measures proxying alone).
#
# Usage: bench/replicas_load.sh [BUILD_DIR]          (default: build)
#   Expects a built BUILD_DIR/server/meshwave-server; builds nothing.
#   Needs postgresql, nginx-light, wrk, curl, jq (installed when root).
# Environment: MESH, TARGET_BYTES, BUDGET, CONNS, DURATION, WRK_THREADS, KEEP
#   as in bench/http_load.sh (DURATION defaults to 5 here).
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
duration=${DURATION:-5}
wrk_threads=${WRK_THREADS:-2}
(( duration >= 1 && duration <= 10 )) || { echo "DURATION must be 1..10 s" >&2; exit 2; }
[[ -x $server_bin ]] || { echo "no meshwave-server at $server_bin (build it first)" >&2; exit 1; }
[[ -r $mesh ]] || { echo "cannot read mesh $mesh" >&2; exit 1; }

pgbin=$(ls -d /usr/lib/postgresql/*/bin 2> /dev/null | sort -V | tail -1)
missing=()
[[ -x $pgbin/postgres ]] || missing+=(postgresql)
command -v nginx > /dev/null || [[ -x /usr/sbin/nginx ]] || missing+=(nginx-light)
for t in wrk curl jq; do command -v $t > /dev/null || missing+=($t); done
if (( ${#missing[@]} )); then
  [[ $(id -u) = 0 ]] || { echo "missing ${missing[*]}; run as root or install them" >&2; exit 1; }
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" >&2
  pgbin=$(ls -d /usr/lib/postgresql/*/bin | sort -V | tail -1)
fi
nginx_bin=$(command -v nginx || echo /usr/sbin/nginx)

tmp=$(mktemp -d /tmp/replicas_load.XXXXXX)
chmod 755 "$tmp"
pids=()
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2> /dev/null || true; done
  for pid in "${pids[@]}"; do
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
# PostgreSQL refuses root: run it (and nginx) as nobody then.
as_user=()
[[ $(id -u) = 0 ]] && as_user=(setpriv --reuid=nobody --regid=nogroup --clear-groups --)
wait_http() { for _ in $(seq 200); do curl -sf -o /dev/null "$1" && return 0; sleep 0.05; done; return 1; }

# --- PostgreSQL ---------------------------------------------------------------
mkdir -p "$tmp/pg"
[[ ${#as_user[@]} -gt 0 ]] && chown nobody "$tmp/pg"
"${as_user[@]}" "$pgbin/initdb" -D "$tmp/pg/data" -U meshwave -A trust --no-sync \
  --no-instructions > "$tmp/pg/initdb.log" 2>&1
pgport=$(free_port)
"${as_user[@]}" "$pgbin/postgres" -D "$tmp/pg/data" -p "$pgport" -k "$tmp/pg" \
  -c listen_addresses=127.0.0.1 > "$tmp/pg/postgres.log" 2>&1 &
pids+=($!)
for _ in $(seq 200); do "$pgbin/pg_isready" -q -h 127.0.0.1 -p "$pgport" && break; sleep 0.05; done
catalog=postgres://meshwave@127.0.0.1:$pgport/postgres

# --- ingest and two replicas ------------------------------------------------------
echo "ingesting $(basename "$mesh") ..." >&2
"$server_bin" ingest --catalog "$catalog" --store "$tmp/store" "$mesh" > "$tmp/ingest.log" 2>&1 ||
  { cat "$tmp/ingest.log" >&2; exit 1; }
replica_ports=()
for r in a b; do
  "$server_bin" --catalog "$catalog" --store "$tmp/store" --listen 127.0.0.1:0 \
    --port-file "$tmp/port-$r" --threads 2 --log-level warn > "$tmp/server-$r.log" 2>&1 &
  pids+=($!)
  for _ in $(seq 200); do [[ -s $tmp/port-$r ]] && break; sleep 0.05; done
  [[ -s $tmp/port-$r ]] || { cat "$tmp/server-$r.log" >&2; exit 1; }
  replica_ports+=("$(tr -d '\n' < "$tmp/port-$r")")
done
S=http://127.0.0.1:${replica_ports[0]}

id=$(curl -sf "$S/v1/meshes" | jq -r '.meshes[0].id')
packets=$(curl -sf "$S/v1/meshes/$id" | jq -r '.mesh.packets')
for (( k = 0; k < packets; ++k )); do
  printf 'url = "%s/v1/meshes/%s/packets/%d"\noutput = "/dev/null"\n' "$S" "$id" "$k"
done > "$tmp/packets.curl"
curl -sf -K "$tmp/packets.curl" -w '%{size_download}\n' > "$tmp/packet_sizes"
read -r pk plen <<< "$(awk -v t="$target_bytes" '{ d = $1 - t; if (d < 0) d = -d;
  if (NR == 1 || d < bd) { bd = d; bk = NR - 1; bl = $1 } } END { print bk, bl }' "$tmp/packet_sizes")"
packet_path=/v1/meshes/$id/packets/$pk
stream_path="/v1/meshes/$id/stream?order=quality&budget=$budget"

# --- nginx: the shipped locations file, a cached and an uncached server ------------
n=$tmp/nginx
mkdir -p "$n/cache" "$n/tmp"
cp "$root/deploy/nginx/meshwave-locations.conf" "$n/"
# The uncached server: the same file with `proxy_cache meshwave;` turned off.
sed 's/^\(\s*\)proxy_cache meshwave;/\1proxy_cache off;/' "$n/meshwave-locations.conf" \
  > "$n/meshwave-locations-nocache.conf"
nport=$(free_port)
nport_nocache=$(free_port)
{
  echo "worker_processes 2; pid $n/nginx.pid; error_log $n/error.log warn;"
  echo "events { worker_connections 4096; }"
  echo "http {"
  echo "  access_log off;"
  echo "  client_body_temp_path $n/tmp/body; proxy_temp_path $n/tmp/proxy;"
  echo "  fastcgi_temp_path $n/tmp/fcgi; uwsgi_temp_path $n/tmp/uwsgi; scgi_temp_path $n/tmp/scgi;"
  echo "  proxy_cache_path $n/cache levels=1:2 keys_zone=meshwave:10m max_size=1g inactive=1h use_temp_path=off;"
  echo "  upstream meshwave_servers {"
  for p in "${replica_ports[@]}"; do echo "    server 127.0.0.1:$p max_fails=1 fail_timeout=10s;"; done
  echo "    keepalive 64;"
  echo "  }"
  echo "  server { listen 127.0.0.1:$nport; include $n/meshwave-locations.conf; }"
  echo "  server { listen 127.0.0.1:$nport_nocache; include $n/meshwave-locations-nocache.conf; }"
  echo "}"
} > "$n/nginx.conf"
[[ ${#as_user[@]} -gt 0 ]] && chown -R nobody "$n"
"${as_user[@]}" "$nginx_bin" -p "$n/" -e "$n/error.log" -c "$n/nginx.conf" -g 'daemon off;' \
  > "$n/stdout.log" 2>&1 &
pids+=($!)
N=http://127.0.0.1:$nport
U=http://127.0.0.1:$nport_nocache
wait_http "$N/healthz" || { cat "$n/error.log" >&2; exit 1; }

# Same bytes everywhere; warm the cache, and check it is warm.
for path in "$packet_path" "$stream_path"; do
  curl -sf -o "$tmp/direct" "$S$path"
  for base in "$N" "$U"; do
    curl -sf -o "$tmp/via" "$base$path"
    cmp -s "$tmp/direct" "$tmp/via" || { echo "different bytes via $base$path" >&2; exit 1; }
  done
  status=$(curl -sf -o /dev/null -D - "$N$path" | awk 'tolower($1) == "x-cache-status:" { print $2 }' | tr -d '\r')
  [[ $status = HIT ]] || { echo "not cached: $N$path ($status)" >&2; exit 1; }
done
packet_bytes=$(stat -c %s "$tmp/via")

# --- wrk -----------------------------------------------------------------------
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
results=$tmp/results.tsv
: > "$results"
for c in $conns_list; do
  for what in packet stream; do
    path=$packet_path; [[ $what = stream ]] && path=$stream_path
    run_wrk "replica-$what" "$S$path" "$c"
    run_wrk "nginx-uncached-$what" "$U$path" "$c"
    run_wrk "nginx-cached-$what" "$N$path" "$c"
  done
done

echo
echo "mesh $(basename "$mesh") (id $id): packet $pk = $packet_bytes bytes; stream order=quality" \
  "budget=$budget; PostgreSQL catalog, 2 replicas (--threads 2 each), nginx" \
  "$("$nginx_bin" -v 2>&1 | sed 's/.*nginx\///') worker_processes 2 with meshwave-locations.conf;" \
  "wrk -t$wrk_threads -d${duration}s; $(nproc) cores shared by all; load before: $load_before;" \
  "after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| target | connections | requests/s | p50 ms | p99 ms | MiB/s | errors |"
echo "|---|---:|---:|---:|---:|---:|---:|"
awk -F'\t' '{ label = $1; gsub(/-/, " ", label);
  printf "| %s | %s | %s | %.2f | %.2f | %s | %s |\n", label, $2, $3, $4, $5, $6, $7 }' "$results"
