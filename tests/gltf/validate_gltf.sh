#!/usr/bin/env bash
# `meshwave decode … out.glb / out.gltf` checked by the Khronos
# glTF-Validator under Node: a sample encoded, decoded whole and at a
# budget into both forms, each valid (no error, no warning) and holding the
# decoded mesh's vertex and triangle counts; a truncated GLB refused.
#
# A sample that is already a stream (.mwv) is decoded as it is; one with a
# texture must give files the validator finds textures in (at least the
# whole stream's).
#
# Usage: validate_gltf.sh WORK_DIR MESHWAVE_CLI SAMPLE_MESH_OR_STREAM
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?work dir} cli=${2:?meshwave binary} sample=${3:?sample mesh}
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v node > /dev/null || fail "node not found (bash deploy/install-deps.sh)"
modules=$(bash "$here/../../web/npm_ci.sh" "$work/npm")
out=$work/out
rm -rf "$out" && mkdir -p "$out"
if [[ $sample == *.mwv ]]; then
  cp "$sample" "$out/s.mwv"
else
  "$cli" encode "$sample" "$out/s.mwv" > /dev/null
fi
textured=no
"$cli" info "$out/s.mwv" 2>/dev/null | grep -q '^texture map:' && textured=yes
files=()
for budget in 6000 all; do
  args=()
  [[ $budget == all ]] || args=(--budget "$budget")
  for ext in glb gltf; do
    f=$out/s_$budget.$ext
    log=$("$cli" decode "$out/s.mwv" "$f" "${args[@]}") || fail "decode to $f"
    # "wrote F: V vertices, T faces (level …)": the validator must count the same.
    counts=$(sed -n 's/^wrote .*: \([0-9]*\) vertices, \([0-9]*\) faces.*/\1 vertices, \2 triangles/p' <<< "$log")
    [[ -n $counts ]] || fail "unexpected decode output: $log"
    report=$(node "$here/validate_gltf.mjs" "$modules" "$f") || { echo "$report"; fail "$f is not valid glTF 2.0"; }
    echo "$report"
    grep -q "; $counts$" <<< "$report" || fail "$f: expected $counts"
    if [[ $textured == yes && $budget == all ]]; then
      grep -q "textures:" <<< "$report" || fail "$f: the stream's texture is missing"
    fi
    files+=("$f")
  done
done
head -c 200 "$out/s_all.glb" > "$out/truncated.glb"
node "$here/validate_gltf.mjs" "$modules" --expect-invalid "$out/truncated.glb" ||
  fail "a truncated GLB passed the validator"
echo "refused as expected: truncated.glb"
echo "validate_gltf: ${#files[@]} files valid"
