#!/usr/bin/env bash
# The textured development assets end to end: each ingested from its
# original files by `meshwave-server ingest` (timed, peak memory), served by
# meshwave-server on 127.0.0.1, fetched by the C++ client (`meshwave fetch`)
# at five budgets into .glb files, each checked by the Khronos
# glTF-Validator (0 errors, 0 warnings) and described (texture level held,
# vertex colours). One TSV line per fetch in OUT/textured_assets.tsv.
# Then the browser viewer streams each at the same budgets
# (textured_assets_viewer.mjs: screenshots, pixels in colour) into
# OUT/textured_assets_viewer.tsv. An existing OUT/catalog is served as it
# is (no ingest): delete it to ingest again.
#
# Usage: bench/textured_assets.sh [BUILD_DIR] [TEXTURED_DIR] [OUT_DIR]
#   defaults: build, ../shared/data/textured, a temporary directory
#   FIDELITY=DB  ingest --fidelity (default: the ingest's own, 84 dB);
#                per asset: FIDELITY_<stem>=DB (e.g. FIDELITY_ToyCar=0)
#   DECODER_JS=FILE  the WebAssembly decoder (default: BUILD_DIR/wasm/web/decoder/
#                meshwave_decoder.js, else web/dist's); the viewer part is skipped
#                without it
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help ]]; then sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0; fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
assets=${2:-$root/../shared/data/textured}
out=${3:-$(mktemp -d)}
[[ -d $assets ]] || { echo "textured_assets: no folder $assets" >&2; exit 1; }
cli=$build/tools/meshwave/meshwave
server=$build/server/meshwave-server
modules=$(bash "$root/web/npm_ci.sh" "$out/npm")
mkdir -p "$out"
catalog=$out/catalog
tsv=$out/textured_assets.tsv
printf 'asset\tbudget\tbytes\tpackets\tvertices\tfaces\ttexture\tcolours\tvalidator\n' > "$tsv"
server_pid=
trap '[[ -n $server_pid ]] && kill "$server_pid" 2> /dev/null; true' EXIT

files=()
for f in "$assets"/*/*.gltf "$assets"/*/*.glb "$assets"/*/*.obj "$assets"/*/*.ply; do
  [[ -e $f ]] && files+=("$f")
done
[[ -d $catalog ]] && { echo "textured_assets: serving the existing $catalog"; files=(); }
for f in "${files[@]}"; do
  stem=$(basename "${f%.*}")
  fidelity_var=FIDELITY_$stem
  fidelity=${!fidelity_var:-${FIDELITY:-}}
  args=()
  [[ -n $fidelity ]] && args=(--fidelity "$fidelity")
  echo "== ingest $f ${args[*]}"
  /usr/bin/time -f "ingest $stem: %e s, peak RSS %M KiB" \
    "$server" ingest --catalog "$catalog" "${args[@]}" "$f" 2>&1 | grep -E "^[0-9a-f]{12} |ingest $stem:|warn|texture" || true
done
decoder=${DECODER_JS:-$build/wasm/web/decoder/meshwave_decoder.js}
[[ -f $decoder ]] || decoder=$root/web/dist/meshwave_decoder.js
viewer_args=()
if [[ -f $decoder ]]; then
  rm -rf "$out/viewer" && cp -r "$root/web/viewer" "$out/viewer" && cp "$decoder" "$out/viewer/"
  viewer_args=(--viewer-dir "$out/viewer")
fi
rm -f "$out/port"
"$server" --catalog "$catalog" --listen 127.0.0.1:0 --port-file "$out/port" --log-level warn "${viewer_args[@]}" \
  > "$out/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do [[ -s $out/port ]] && break; sleep 0.1; done
url=http://127.0.0.1:$(cat "$out/port")
"$cli" catalog "$url" | tee "$out/catalog.txt"
while read -r id name _; do
  [[ $id =~ ^[0-9a-f]{12}$ ]] || continue
  total=$(curl -s "$url/v1/meshes/$id" | sed -n 's/.*"bytes": *"\{0,1\}\([0-9]*\).*/\1/p' | head -n 1)
  for share in 5 15 35 65 100; do
    budget=$(( total * share / 100 ))
    glb=$out/${name}_$share.glb
    line=$("$cli" fetch "$url/v1/meshes/$id" --budget "$budget" --out "$glb" 2>&1 | tr '\n' ' ')
    report=$(node "$root/tests/gltf/validate_gltf.mjs" "$modules" "$glb" 2>&1 | tr '\n' ' ' || true)
    packets=$(sed -n 's/.* \([0-9]*\) packets.*/\1/p' <<< "$line" | head -n 1)
    vertices=$(sed -n 's/.*: \([0-9]*\) vertices, \([0-9]*\) faces.*/\1/p' <<< "$line" | head -n 1)
    faces=$(sed -n 's/.*: \([0-9]*\) vertices, \([0-9]*\) faces.*/\2/p' <<< "$line" | head -n 1)
    texture=$(grep -o 'textured: [^)]*)' <<< "$line" | head -n 1 | sed 's/textured: //' || true)
    colours=$(grep -q 'with vertex colours' <<< "$line" && echo yes || echo no)
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$share%" "$budget" "${packets:-?}" \
      "${vertices:-?}" "${faces:-?}" "${texture:--}" "$colours" "$report" >> "$tsv"
  done
done < "$out/catalog.txt"
column -t -s $'\t' "$tsv"
echo "textured_assets: $tsv"
if [[ ${#viewer_args[@]} -gt 0 ]]; then
  node "$root/bench/textured_assets_viewer.mjs" --url "$url" --catalog "$out/catalog.txt" \
    --node-modules "$modules" --out "$out"
else
  echo "textured_assets: no WebAssembly decoder ($decoder): the viewer part is skipped"
fi
