#!/usr/bin/env bash
# SAWT (Denis et al. 2010a) against the default transform in rate-distortion, on every
# shared mesh (docs/ANALYSIS.md, "SAWT"):
#   1. each mesh is made semi-regular once (`meshwave remesh`, cached in
#      $CACHE as bench/analysis_table.sh does; semi-regular files as they are);
#   2. `meshwave rd --coders 3xc --json` with the default (lifted butterfly),
#      unlifted butterfly, SAWT (unlifted, its default) and SAWT lifted
#      (--update constant); PSNR differences at 0.05, 0.1, 0.2, 0.3, 0.5 bpv
#      (base excluded) and their mean;
#   3. `meshwave encode --transform sawt` for the regions and how often each
#      filter f1..f6 was chosen (coded (level, region) pairs) and the bytes
#      of the header field.
# Extra rd options (e.g. --sawt-lambda 16) go in $SAWT_OPTS.
# Output: Markdown on stdout.
#
# Usage: bench/sawt_table.sh [BUILD_DIR]   (needs jq)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
cache=${CACHE:-/tmp/meshwave-analysis-cache}
read -r -a sawt_opts <<< "${SAWT_OPTS:-}"
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
command -v jq > /dev/null || { echo "jq is needed (apt-get install jq)" >&2; exit 1; }
mkdir -p "$cache"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source "$root/bench/lib.sh"

# delta A B [SIDE_BPV]: "mean<TAB>d1 d2 d3 d4 d5" of PSNR(B) - PSNR(A) at the rd
# table's rates, B's curve read SIDE_BPV lower: the rd rates count payload
# bytes only, so SAWT's header field is charged to it this way.
delta() {
  if [[ $(jq '.curves[0].table | length' "$2") == 0 ]]; then printf 'n/a\tn/a\n'; return; fi
  python3 - "$1" "$2" "${3:-0}" << 'PY'
import json, sys
def psnr_at(points, bpv):
    for a, b in zip(points, points[1:]):
        if a["bpv_excl_base"] <= bpv <= b["bpv_excl_base"]:
            if b["bpv_excl_base"] == a["bpv_excl_base"]:
                return b["psnr_db"]
            t = (bpv - a["bpv_excl_base"]) / (b["bpv_excl_base"] - a["bpv_excl_base"])
            return a["psnr_db"] + t * (b["psnr_db"] - a["psnr_db"])
    return float("nan")
a, b = (json.load(open(f))["curves"][0]["points"] for f in sys.argv[1:3])
side = float(sys.argv[3])
d = [psnr_at(b, r - side) - psnr_at(a, r) for r in (0.05, 0.1, 0.2, 0.3, 0.5)]
print("%+.3f\t%s" % (sum(d) / len(d), " ".join("%+.3f" % x for x in d)))
PY
}

names=()
for path in "$meshes"/*.ply "$meshes"/*.obj; do [[ -f $path ]] && names+=("$(basename "$path")"); done
: > "$tmp/rows.tsv"
for name in "${names[@]}"; do
  sr=$(semi_regular "$name") || { echo "remesh failed: $name" >&2; continue; }
  b=$tmp/${name%.*}
  nice "$cli" rd "$sr" --coders 3xc --json > "$b.default.json" 2> /dev/null
  nice "$cli" rd "$sr" --coders 3xc --update none --json > "$b.unlifted.json" 2> /dev/null
  nice "$cli" rd "$sr" --coders 3xc --transform sawt "${sawt_opts[@]}" --json > "$b.sawt.json" 2> /dev/null
  nice "$cli" rd "$sr" --coders 3xc --transform sawt --update constant "${sawt_opts[@]}" --json \
    > "$b.sawt_lifted.json" 2> "$b.lifted.err" ||
    { echo '{"curves":[{"table":[]}]}' > "$b.sawt_lifted.json"; echo "$name lifted: $(cat "$b.lifted.err")" >&2; }
  enc=$(nice "$cli" encode "$sr" "$tmp/s.mwv" --transform sawt "${sawt_opts[@]}" 2> /dev/null | grep '^sawt:')
  regions=$(sed -E 's/^sawt: ([0-9]+) regions.*/\1/' <<< "$enc")
  field=$(sed -E 's/.*header field ([0-9]+) bytes.*/\1/' <<< "$enc")
  usage=$(sed -E 's/.*choices per filter //' <<< "$enc")
  v=$(jq -r '.vertices' "$b.default.json")
  side=$(awk -v f="$field" -v v="$v" 'BEGIN { printf "%.6f", 8 * f / v }')
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$v" "$regions" "$field" \
    "$(delta "$b.default.json" "$b.sawt.json" "$side")" \
    "$(delta "$b.unlifted.json" "$b.sawt.json" "$side" | cut -f1)" \
    "$(delta "$b.default.json" "$b.sawt_lifted.json" "$side" | cut -f1)" "$usage" >> "$tmp/rows.tsv"
  echo "done $name" >&2
done
echo "PSNR differences in dB (3xC, base excluded, SAWT's header field charged to its rate), mean"
echo "over 0.05, 0.1, 0.2, 0.3, 0.5 bpv:"
echo "SAWT (unlifted, the default with \`--transform sawt\`) against the default lifted butterfly, the"
echo "same at each rate, SAWT against the unlifted butterfly, and lifted SAWT (\`--update constant\`)"
echo "against the default (n/a: the encoder refused, see docs/ANALYSIS.md). Regions: octree leaves at alpha = 400; field: bytes of \`transform.sawt\`;"
echo "filters: coded (level, region) choices per filter."
echo
echo "| Mesh | V | regions | field B | SAWT - default | at 0.05 / 0.1 / 0.2 / 0.3 / 0.5 | SAWT - unlifted BF | lifted SAWT - default | f1..f6 chosen |"
echo "|---|---:|---:|---:|---:|---|---:|---:|---|"
awk -F'\t' '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9;
              a += $5; u += $7; if ($8 != "n/a") { l += $8; nl++ } }
            END { printf "| **mean** | | | | %+.3f | | %+.3f | %s | |\n", a / NR, u / NR,
                         nl ? sprintf("%+.3f", l / nl) : "n/a" }' "$tmp/rows.tsv"
echo
echo "Generated by \`bench/sawt_table.sh\` at commit $(git -C "$root" rev-parse --short HEAD)."
