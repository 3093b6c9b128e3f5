#!/usr/bin/env bash
# Regenerates the measurements of docs/ANALYSIS.md over the shared meshes:
#   1. each mesh is made semi-regular once (`meshwave remesh`, cached in
#      $CACHE, default /tmp/meshwave-analysis-cache; semi-regular files are
#      used as they are);
#   2. `meshwave analyze --json` on each: Tables 1-3 (KL / ME per component,
#      per subband, mutual information), written as Markdown;
#   3. `meshwave rd --coders 3xc` with --quantizer saq (default) and auto:
#      mean PSNR difference over 0.05-0.5 bpv;
#   4. figures for one mesh ($PLOT_MESH): `meshwave analyze --plots` with a
#      Draco curve (draco_encoder -cl 10 -qp 6..12, measured with `meshwave
#      compare --match nearest`), and a strip rendered at five budgets.
# Output: Markdown on stdout, figures in docs/analysis/.
#
# Usage: bench/analysis_table.sh [BUILD_DIR]   (needs jq, gnuplot, optional draco)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
cache=${CACHE:-/tmp/meshwave-analysis-cache}
plot_mesh=${PLOT_MESH:-elephant_subdiv2.ply}
figs=$root/docs/analysis
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
for tool in jq gnuplot; do
  command -v $tool > /dev/null || { echo "$tool is needed (apt-get install jq gnuplot-nox)" >&2; exit 1; }
done
mkdir -p "$cache" "$figs"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source "$root/bench/lib.sh"

names=()
for path in "$meshes"/*.ply "$meshes"/*.obj; do [[ -f $path ]] && names+=("$(basename "$path")"); done

echo "### Model fits (Satti et al. 2011, Tables 1-2)"
echo
echo "KL divergence in bits (ME in %), lifted butterfly, local frames; Table 1 columns average the"
echo "analysed subbands (the five finest, or fewer when the mesh has fewer levels), Table 2 rows the"
echo "three components. **Bold**: the best of SL, LM, GG in the row (by KL)."
echo
echo "| Mesh | V | J | comp. | SL | LM | GG | LM best KL? | LM best ME? |"
echo "|---|---:|---:|---|---:|---:|---:|---|---|"
: > "$tmp/mi.md"
: > "$tmp/t2.md"
: > "$tmp/rd.tsv"
for name in "${names[@]}"; do
  sr=$(semi_regular "$name") || { echo "remesh failed: $name" >&2; continue; }
  json=$tmp/${name%.*}.json
  nice "$cli" analyze "$sr" --json > "$json" 2> /dev/null || { echo "analyze failed: $name" >&2; continue; }
  cp "$json" "$cache/${name%.*}.analysis.json"
  jq -r --arg name "$name" '
    def fmt(k; m): (k*1000|round/1000|tostring) + " (" + (m*10|round/10|tostring) + ")";
    . as $r | ["normal","tangent 1","tangent 2"] | to_entries[] | .key as $c | .value as $cn
    | [$r.components[] | select(.component == $c)] as $s
    | {sl: ([$s[].SL_kl]|add/length), lm: ([$s[].LM_kl]|add/length), gg: ([$s[].GG_kl]|add/length),
       slm: ([$s[].SL_me]|add/length), lmm: ([$s[].LM_me]|add/length), ggm: ([$s[].GG_me]|add/length)} as $m
    | "| \($name) | \($r.vertices) | \($r.levels) | \($cn) | " +
      ([[$m.sl,$m.slm],[$m.lm,$m.lmm],[$m.gg,$m.ggm]] | ([.[][0]]|min) as $best
        | map(if .[0] == $best then "**" + fmt(.[0]; .[1]) + "**" else fmt(.[0]; .[1]) end) | join(" | ")) +
      " | " + (if $m.lm <= ([$m.sl,$m.gg]|min) then "yes" else "no" end) +
      " | " + (if $m.lmm <= ([$m.slm,$m.ggm]|min) then "yes" else "no" end) + " |"' "$json"
  jq -r --arg name "$name" '
    def fmt(k; m): (k*1000|round/1000|tostring) + " (" + (m*10|round/10|tostring) + ")";
    . as $r | [.components[].subband] | unique | reverse | .[:3][] as $j
    | [$r.components[] | select(.subband == $j)] as $s
    | "| \($name) | d^\($j) (J-\($r.levels - $j)) | " +
      fmt([$s[].SL_kl]|add/length; [$s[].SL_me]|add/length) + " | " +
      fmt([$s[].LM_kl]|add/length; [$s[].LM_me]|add/length) + " | " +
      fmt([$s[].GG_kl]|add/length; [$s[].GG_me]|add/length) + " |"' "$json" >> "$tmp/t2.md"
  jq -r --arg name "$name" '
    def r: (.*10000|round/10000);
    . as $r | if (.mutual_information | length) == 0 then empty else
    (.mutual_information | {a: ([.[].intraband]|add/length), e: ([.[].interband]|add/length),
                             c: ([.[].composite]|add/length)}) as $m
    | "| \($name) | \([$r.mutual_information[].subband]|unique|length) | \($m.a|r) | \($m.e|r) | \($m.c|r) | " +
      (if $m.e < $m.a and $m.a < $m.c then "yes" else "no" end) + " |" end' "$json" >> "$tmp/mi.md"
  # RD: default (SAQ) against --quantizer auto, 3xC.
  nice "$cli" rd "$sr" --coders 3xc --json > "$tmp/saq.json" 2> /dev/null
  nice "$cli" rd "$sr" --coders 3xc --quantizer auto --json > "$tmp/auto.json" 2> /dev/null
  zs=$(jq -r '[.components[].auto_deadzone] | group_by(.) | map("\(.[0]):\(length)") | join(" ")' "$json")
  paste <(jq -r '.curves[0].table[].psnr_db' "$tmp/saq.json") <(jq -r '.curves[0].table[].psnr_db' "$tmp/auto.json") |
    awk -v n="$name" -v zs="$zs" '{ d = $2 - $1; s += d; printf "%s%+.3f", (NR > 1 ? " " : ""), d > "/dev/stderr" }
        END { printf "\t%s\t%+.3f\t%s\n", n, s / NR, zs }' 2> "$tmp/deltas" >> "$tmp/rd.tsv"
  sed -i "\$s/\$/\t$(cat "$tmp/deltas")/" "$tmp/rd.tsv"
done
echo
echo "| Mesh | subband | SL | LM | GG |"
echo "|---|---|---:|---:|---:|"
cat "$tmp/t2.md"
echo
echo "### Mutual information (Satti et al. 2011, Table 3)"
echo
echo "Bits, averaged over the three components and the analysed subbands with a parent (d^1 and finer);"
echo "intraband I(X;T), T = sum of squared same-subband neighbours; interband I(X;P); composite I(X;(P,T))."
echo
echo "| Mesh | subbands | intraband | interband | composite | inter < intra < composite? |"
echo "|---|---:|---:|---:|---:|---|"
cat "$tmp/mi.md"
echo
echo "### \`--quantizer auto\` against SAQ (3xC, lifted butterfly)"
echo
echo "PSNR(auto) - PSNR(SAQ) in dB at 0.05, 0.1, 0.2, 0.3, 0.5 bpv (base excluded) and their mean;"
echo "deadzone codes chosen in the analysed subbands (0 SAQ, 1 UEQ, 2 z=1.5, 3 z=2.5: count)."
echo
echo "| Mesh | mean dPSNR | at 0.05 / 0.1 / 0.2 / 0.3 / 0.5 | codes chosen |"
echo "|---|---:|---|---|"
awk -F'\t' '{ printf "| %s | %s | %s | %s |\n", $2, $3, $5, $4; m += $3 } END { printf "| **mean** | %+.3f | | |\n", m / NR }' "$tmp/rd.tsv"
echo
echo "Generated by \`bench/analysis_table.sh\` at commit $(git -C "$root" rev-parse --short HEAD)."
