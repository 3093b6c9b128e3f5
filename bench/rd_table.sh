#!/usr/bin/env bash
# Regenerates the tables of docs/RD_RESULTS.md: `meshwave rd` (3xC, SIM, PGC)
# on the shared semi-regular meshes and on remeshed irregular ones. Replaces
# what lies between the rd_table markers in the document; the text around
# them is left alone.
#
# Usage: bench/rd_table.sh [BUILD_DIR]      (default: build; needs jq)
#   MESHWAVE_SHARED_MESHES overrides the mesh directory.
# Takes about 30 s on two idle cores (remeshing included).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
doc=$root/docs/RD_RESULTS.md
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 1; }
grep -q '<!-- rd_table:begin -->' "$doc" || { echo "$doc has no rd_table markers" >&2; exit 1; }

# file [extra rd options]: the semi-regular ones first, then remeshed ones.
cases=(
  "elephant_subdiv2.ply"
  "elephant_cartoon_sr2.obj"
  "holes_patch_sr2.ply"
  "bunny_stanford_zipper.ply"
  "bunny_stanford_zipper.ply --levels 5"
  "horse_cyberware.ply"
)

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$tmp/tables.md
deltas=$tmp/deltas.tsv  # case, bpv, 3xc-pgc, 3xc-sim, sim-pgc

n=0
# run_cases DETAIL COMMON_OPTIONS: every case with COMMON_OPTIONS added; with
# DETAIL = 1 a section per case, always the mean differences.
run_cases() {
  local detail=$1 common=$2
  : > "$deltas"
  for c in "${cases[@]}"; do
    read -r file extra <<< "$c"
    extra=$(echo "$extra $common" | xargs)
    n=$((n + 1))
    json=$tmp/$n.json
    # shellcheck disable=SC2086  # extra options split on purpose
    # Equal steps for the three components: the coders are compared on the
    # vertex error, as Satti et al. 2011 does (docs/RD_RESULTS.md,
    # "Tangential step").
    "$cli" rd "$meshes/$file" --coders 3xc,sim,pgc --tangent-step 1 $extra --json > "$json" 2> "$tmp/$n.log"
    jq -r --arg file "$file" --arg extra "$extra" '
      "### \($file)\(if $extra == "" then "" else " (" + $extra + ")" end)\n",
      "\(if .remeshed then "Remeshed (not semi-regular as read)" else "Semi-regular as read" end): " +
      "\(.vertices) vertices, J = \(.levels), \(.base_vertices) base vertices; " +
      "\(.transform)/\(.update), precision \(.precision).\n",
      "Command: `meshwave rd \($file) --coders 3xc,sim,pgc --tangent-step 1\(if $extra == "" then "" else " " + $extra end)`\n"
    ' "$json" > "$tmp/head.md"

    # PSNR at the table rates.
    {
      cat "$tmp/head.md"
      echo "| PSNR [dB] at bpv (base excluded) | 0.05 | 0.1 | 0.2 | 0.3 | 0.5 | base bpv | full bpv |"
      echo "|---|---:|---:|---:|---:|---:|---:|---:|"
      jq -r '.curves[] | [.coder, (.table[].psnr_db), .points[0].bpv_total, .points[-1].bpv_total] | @tsv' "$json" |
        awk -F'\t' '{ printf "| %s |", $1; for (i = 2; i <= 6; ++i) printf " %.2f |", $i;
                      printf " %.3f | %.3f |\n", $7, $8 }'
      jq -r '[.curves[] | {(.coder): [.table[].psnr_db]}] | add
             | [range(0; 5) as $i | [.["3xc"][$i], .["sim"][$i], .["pgc"][$i]]] | .[] | @tsv' "$json" |
        awk -F'\t' '{ a[NR] = $1 - $3; b[NR] = $1 - $2 }
                    END { printf "| 3xC - PGC |"; for (i = 1; i <= NR; ++i) printf " %+.2f |", a[i]; print " | |";
                          printf "| 3xC - SIM |"; for (i = 1; i <= NR; ++i) printf " %+.2f |", b[i]; print " | |" }'
      echo
    } > "$tmp/psnr.md"
    jq -r --arg case "$n" '[.curves[] | {(.coder): [.table[] | [.bpv_excl_base, .psnr_db]]}] | add
           | range(0; 5) as $i
           | [$case, .["3xc"][$i][0], .["3xc"][$i][1] - .["pgc"][$i][1],
              .["3xc"][$i][1] - .["sim"][$i][1], .["sim"][$i][1] - .["pgc"][$i][1]] | @tsv' \
      "$json" >> "$deltas"

    # Rates at equal quality: where each coder completes bitplane b.
    {
      echo "<details><summary>Rate at equal quality (bpv, base excluded, when bitplane b is complete)</summary>"
      echo
      echo "| b | PSNR [dB] | 3xC | SIM | PGC | 3xC / PGC | SIM / PGC |"
      echo "|---:|---:|---:|---:|---:|---:|---:|"
      jq -r '[.curves[] | {(.coder): [.points[] | select(.bitplane_complete >= 0)
                                      | {key: (.bitplane_complete | tostring), value: .}] | from_entries}] | add
             | . as $c | $c["pgc"] | keys_unsorted[] as $b
             | [$b, $c["pgc"][$b].psnr_db, $c["3xc"][$b].bpv_excl_base, $c["sim"][$b].bpv_excl_base,
                $c["pgc"][$b].bpv_excl_base] | @tsv' "$json" |
        awk -F'\t' '{ printf "| %d | %.2f | %.4f | %.4f | %.4f | %.3f | %.3f |\n", $1, $2, $3, $4, $5,
                      $3 / $5, $4 / $5 }'
      echo
      echo "</details>"
      echo
    } > "$tmp/rate.md"
    # The Bunny figures of Satti et al. 2011 (3xC, Fig. 11, base excluded) beside ours
    # at its rates, interpolated between our packet points.
    if [[ $file == bunny* ]]; then
      {
        echo "Beside the Bunny of Satti et al. 2011 (3xC, its Fig. 11, base mesh excluded; ours interpolated at its rates):"
        echo
        echo "| PSNR [dB] at bpv (base excluded) | 0.050 | 0.098 | 0.178 | 0.314 | 0.540 |"
        echo "|---|---:|---:|---:|---:|---:|"
        echo "| Satti et al. 2011, 3xC (their Bunny remesh) | 47.6 | 51.4 | 55.4 | 59.2 | 63.1 |"
        for coder in 3xc pgc; do
          jq -r --arg c "$coder" '.curves[] | select(.coder == $c) | .points[] | [.bpv_excl_base, .psnr_db] | @tsv' "$json" |
            awk -F'\t' -v coder="$coder" -v rates="0.050 0.098 0.178 0.314 0.540" '
              { x[NR] = $1; y[NR] = $2 }
              END { n = split(rates, r, " "); printf "| ours %s (this remesh) |", coder
                    for (i = 1; i <= n; ++i) {
                      v = "-"
                      for (k = 2; k <= NR; ++k) if (x[k] >= r[i]) {
                        v = sprintf("%.2f", y[k-1] + (y[k] - y[k-1]) * (r[i] - x[k-1]) / (x[k] - x[k-1])); break }
                      printf " %s |", v }
                    print "" }'
        done
        echo
      } > "$tmp/seed.md"
    else
      : > "$tmp/seed.md"
    fi
    if [[ $detail == 1 ]]; then
      cat "$tmp/psnr.md" "$tmp/seed.md" "$tmp/rate.md" >> "$out"
    fi
  done

  # Mean PSNR differences over all cases.
  {
    echo "### Mean over the ${#cases[@]} cases${common:+ with $common}"
    echo
    echo "| mean PSNR difference [dB] | 0.05 | 0.1 | 0.2 | 0.3 | 0.5 | all |"
    echo "|---|---:|---:|---:|---:|---:|---:|"
    awk -F'\t' '{ k = (NR - 1) % 5; x[k] += $3; s[k] += $4; p[k] += $5; ++m[k]; tx += $3; ts += $4; tp += $5 }
                END { printf "| 3xC - PGC |"; for (k = 0; k < 5; ++k) printf " %+.2f |", x[k] / m[k]; printf " %+.2f |\n", tx / NR;
                      printf "| 3xC - SIM |"; for (k = 0; k < 5; ++k) printf " %+.2f |", s[k] / m[k]; printf " %+.2f |\n", ts / NR;
                      printf "| SIM - PGC |"; for (k = 0; k < 5; ++k) printf " %+.2f |", p[k] / m[k]; printf " %+.2f |\n", tp / NR }' "$deltas"
    echo
  } >> "$out"
}

run_cases 1 ""
# The octree leaf size of SIM and 3xC matters (docs/RD_RESULTS.md): the same
# cases with larger leaves, summary only.
run_cases 0 "--leaf-size 8"
run_cases 0 "--leaf-size 32"
{
  echo "Generated by \`bench/rd_table.sh\` with $("$cli" --version)" \
       "at commit $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- codec tools || echo ' (plus uncommitted changes)')."
} >> "$out"

# Splice between the markers.
awk -v tables="$out" '
  /<!-- rd_table:begin -->/ { print; while ((getline line < tables) > 0) print line; skip = 1; next }
  /<!-- rd_table:end -->/ { skip = 0 }
  !skip { print }
' "$doc" > "$tmp/doc.md"
mv "$tmp/doc.md" "$doc"
echo "updated $doc"
