# Shell helpers shared by the bench scripts (sourced, not run): a free
# loopback port, wrk's units converted, one wrk run appended to a results
# table, and the cached semi-regular version of a shared mesh.

# need_tools TOOL...: exits with a line naming the first one missing.
need_tools() {
  local tool
  for tool in "$@"; do
    command -v "$tool" > /dev/null ||
      { echo "$tool is needed (bash deploy/install-deps.sh bench)" >&2; exit 1; }
  done
}

# free_port: a 127.0.0.1 port nothing answered on a moment ago.
free_port() {
  local p
  for _ in $(seq 100); do
    p=$(( 20000 + RANDOM % 40000 ))
    (exec 3<> "/dev/tcp/127.0.0.1/$p") 2> /dev/null || { echo "$p"; return; }
  done
  echo "no free port found" >&2; return 1
}

# to_ms VALUE-WITH-UNIT, to_mbs VALUE-WITH-UNIT: wrk's latency and transfer
# figures (its units; bytes are 1024-based) as milliseconds and MiB.
to_ms() { awk -v v="$1" 'BEGIN { n = v + 0; u = v; sub(/^[0-9.]+/, "", u);
  f = (u == "us") ? 0.001 : (u == "ms") ? 1 : (u == "s") ? 1000 : (u == "m") ? 60000 : 0;
  printf "%.3f", n * f }'; }
to_mbs() { awk -v v="$1" 'BEGIN { n = v + 0; u = v; sub(/^[0-9.]+/, "", u);
  f = (u == "B") ? 1 / 1048576 : (u == "KB") ? 1 / 1024 : (u == "MB") ? 1 : (u == "GB") ? 1024 : 0;
  printf "%.1f", n * f }'; }

# run_wrk NAME URL CONNECTIONS: one wrk run of $duration seconds with
# $wrk_threads threads; appends "name conns rps p50_ms p99_ms MiB/s errors"
# to $results (its raw output stays in $tmp).
run_wrk() {
  local name=$1 url=$2 c=$3 out=$tmp/wrk-$1-$3.txt
  echo "wrk -t$wrk_threads -c$c -d${duration}s --latency $url" >&2
  timeout $(( duration + 20 )) wrk -t"$wrk_threads" -c"$c" -d"${duration}s" --timeout 5s --latency "$url" \
    > "$out" 2>&1 || { cat "$out" >&2; exit 1; }
  local rps p50 p99 tr errs
  rps=$(awk '/^Requests\/sec:/ { print $2 }' "$out")
  p50=$(to_ms "$(awk '$1 == "50%" { print $2 }' "$out")")
  p99=$(to_ms "$(awk '$1 == "99%" { print $2 }' "$out")")
  tr=$(to_mbs "$(awk '/^Transfer\/sec:/ { print $2 }' "$out")")
  errs=$(awk '/Non-2xx/ { n += $NF } /Socket errors/ { gsub(/,/, ""); n += $4 + $6 + $8 + $10 }
    END { print n + 0 }' "$out")
  printf '%s\t%s\t%.0f\t%s\t%s\t%s\t%s\n' "$name" "$c" "$rps" "$p50" "$p99" "$tr" "$errs" >> "$results"
}

# semi_regular NAME: path of the semi-regular version of shared mesh NAME
# ($meshes/NAME as it is when `meshwave info` finds levels, otherwise
# `meshwave remesh`'s output cached in $cache). Needs $cli, $meshes, $cache, jq.
semi_regular() {
  local name=$1 src=$meshes/$1
  if "$cli" info "$src" --json 2> /dev/null | jq -e '.semiregular_levels > 0' > /dev/null 2>&1; then
    echo "$src"; return
  fi
  local out=$cache/${name%.*}.sr.ply
  [[ -f $out ]] || "$cli" remesh "$src" "$out" > /dev/null 2> "$cache/${name%.*}.remesh.log"
  echo "$out"
}

# shared_meshes_of_at_least V: the shared meshes (.ply, .obj in $shared) of
# at least V vertices as read, space-separated; exits when $shared is
# missing (a lone clone: name meshes in $MESHES instead). Needs $cli, jq.
shared_meshes_of_at_least() {
  [[ -d $shared ]] || { echo "no shared meshes at $shared: set MESHES" >&2; exit 1; }
  local m v list=
  for m in "$shared"/*.ply "$shared"/*.obj; do
    v=$("$cli" info "$m" --json 2> /dev/null | jq -r '.as_read.vertices // 0')
    (( v >= $1 )) && list="$list $m"
  done
  echo "$list"
}

# surface_psnr ORIGINAL DECODED: the symmetric surface PSNR of DECODED
# against ORIGINAL as `meshwave compare` gives it (peak = the original's
# bounding-box diagonal). Needs $cli, jq.
surface_psnr() { "$cli" compare "$1" "$2" --json | jq '.surface.rms.psnr_db'; }

# rd_prefix MESH STREAM TARGET_DB: "bytes vertices" of the smallest rd-order
# prefix of STREAM whose decoded mesh (as `meshwave decode` writes it)
# reaches TARGET_DB against MESH, or "- -": a bisection over the budget
# (prefixes are whole packets, so it is exact at packet granularity; it
# relies on the rd order's PSNR never decreasing). Caches the PSNR of each
# prefix, keyed by mesh, stream path and size, and packet count (a path
# may be reused for another stream). Needs $cli, $tmp, jq, bc.
declare -A rd_prefix_cache
rd_prefix() {
  local mesh=$1 stream=$2 target=$3
  local size; size=$(stat -c %s "$stream")
  local lo=0 hi=$size found=
  # Invariant: budget hi reaches the target (checked first), lo does not.
  measure() {  # measure BUDGET -> sets m_psnr m_bytes m_vertices m_key
    local j; j=$("$cli" decode --json --order rd --budget "$1" "$stream" "$tmp/p.ply" 2> /dev/null) ||
      { m_psnr=-1; m_bytes=0; m_vertices=0; m_key=none; return; }
    m_bytes=$(jq -r .bytes <<< "$j"); m_vertices=$(jq -r .vertices <<< "$j")
    m_key="$mesh:$stream:$size:$(jq -r .packets <<< "$j")"
    if [[ -z ${rd_prefix_cache[$m_key]:-} ]]; then
      rd_prefix_cache[$m_key]=$(surface_psnr "$mesh" "$tmp/p.ply")
    fi
    m_psnr=${rd_prefix_cache[$m_key]}
  }
  measure "$hi"
  if (( $(echo "$m_psnr < $target" | bc -l) )); then echo "- -"; return; fi
  found="$m_bytes $m_vertices"
  while (( hi - lo > 1 )); do
    local mid=$(( (lo + hi) / 2 ))
    measure "$mid"
    if (( $(echo "$m_psnr >= $target" | bc -l) )); then
      hi=$m_bytes; found="$m_bytes $m_vertices"   # jump to the prefix's real size
    else
      lo=$mid
    fi
  done
  echo "$found"
}

# shared_meshes: the shared development meshes the tables run on (all but
# the small holes patch), one path per line; $MESHES wins when set. Exits
# with a line when there are none.
shared_meshes() {
  if [[ -n ${MESHES:-} ]]; then
    printf '%s\n' $MESHES
    return
  fi
  local dir=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes} found
  found=$(ls "$dir"/*.ply "$dir"/*.obj 2> /dev/null | grep -v holes_patch || true)
  [[ -n $found ]] || { echo "no meshes (set MESHES or put ../shared beside the clone)" >&2; exit 1; }
  echo "$found"
}
