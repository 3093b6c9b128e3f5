#!/usr/bin/env bash
# Regenerates the table of docs/REMESH_RESULTS.md: `meshwave remesh` at its
# default settings on every shared mesh, the result checked by
# `meshwave info` (semi-regular levels found) and measured by
# `meshwave compare` (symmetric surface distance, default sampling).
# Replaces what lies between the remesh_table markers in the document.
#
# Usage: bench/remesh_table.sh [BUILD_DIR]   (default: build; needs jq)
#        bench/remesh_table.sh --big [BUILD_DIR]
#   --big: the 1 M-triangle timing instead (igea.ply subdivided once with
#   Loop), with /usr/bin/time -v; prints the figures, edits nothing.
#   MESHWAVE_SHARED_MESHES overrides the mesh directory.
# The table takes about a minute on two idle cores, --big about 30 s.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
big=0
if [[ ${1:-} == --big ]]; then big=1; shift; fi
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
doc=$root/docs/REMESH_RESULTS.md
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [[ $big == 1 ]]; then
  [[ -x /usr/bin/time ]] || { echo "/usr/bin/time is needed" >&2; exit 1; }
  "$cli" subdivide "$meshes/igea.ply" "$tmp/igea1.ply" --levels 1 --scheme loop
  /usr/bin/time -v "$cli" remesh "$tmp/igea1.ply" "$tmp/igea1_sr.ply" \
    --json --no-measure > "$tmp/big.json" 2> "$tmp/time.txt"
  jq -r '"input: \(.input_vertices) vertices, \(.input_faces) faces\n" +
         "result: J = \(.levels), \(.base_faces) base faces, \(.finest_vertices) vertices, \(.finest_faces) faces\n" +
         "flipped \(.flipped_faces), degenerate \(.degenerate_faces)\n" +
         "remesh time (library): \(.seconds * 100 | round / 100) s; stages: \(.stage_seconds | to_entries | map("\(.key) \(.value * 10 | round / 10) s") | join(", "))"' \
    "$tmp/big.json"
  grep -E "Elapsed|Maximum resident|User time|System time" "$tmp/time.txt"
  exit 0
fi

grep -q '<!-- remesh_table:begin -->' "$doc" || { echo "$doc has no remesh_table markers" >&2; exit 1; }
out=$tmp/table.md
{
  echo "| Mesh | Input V | J | Base F | Finest V | Finest / input | SR levels (info) | RMS % diag | Hausdorff % diag | Flipped | Degenerate | Min angle ° | Time s |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
} > "$out"
status=0
for path in "$meshes"/*.ply "$meshes"/*.obj "$meshes"/*.off; do
  [[ -e $path ]] || continue
  name=$(basename "$path")
  result=$tmp/${name%.*}_sr.ply
  if ! "$cli" remesh "$path" "$result" --json --no-measure > "$tmp/r.json" 2> "$tmp/r.err"; then
    echo "| $name | remesh failed: $(tr '\n' ' ' < "$tmp/r.err") |||||||||||" >> "$out"
    status=1
    continue
  fi
  "$cli" info "$result" --json > "$tmp/i.json"
  "$cli" compare "$path" "$result" --json > "$tmp/c.json"
  jq -r --arg name "$name" --slurpfile info "$tmp/i.json" --slurpfile cmp "$tmp/c.json" '
    def f(x; n): (x * pow(10; n) | round) / pow(10; n);
    "| \($name) | \(.input_vertices) | \(.levels) | \(.base_faces) | \(.finest_vertices) | " +
    "\(f((.finest_vertices | tonumber) / (.input_vertices | tonumber); 2)) | " +
    "\($info[0].semiregular_levels) | " +
    "\(f($cmp[0].surface.rms.percent_of_diagonal; 4)) | " +
    "\(f($cmp[0].surface.hausdorff.percent_of_diagonal; 3)) | " +
    "\(.flipped_faces) | \(.degenerate_faces) | \(f(.min_angle_degrees; 2)) | " +
    "\(f(.seconds; 1)) |"' "$tmp/r.json" >> "$out"
done
# Splice the table between the markers.
awk -v table="$out" '
  /<!-- remesh_table:begin -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
  /<!-- remesh_table:end -->/ { skip = 0 }
  !skip' "$doc" > "$tmp/doc.md"
cp "$tmp/doc.md" "$doc"
cat "$out"
exit $status
