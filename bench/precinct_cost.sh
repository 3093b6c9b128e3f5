#!/usr/bin/env bash
# What precincts cost the uniform orders (issue 21): `meshwave rd` (3xC, rd
# order, packet by packet) on each shared mesh, once without precincts
# (--precinct-size 0) and once at the default, the same remesh both times.
# Prints the complete streams' sizes and, at 5, 10, 25, 50 and 90 % of the
# complete stream without precincts, the PSNR each stream reaches with that
# many bytes (header included) and the difference, both curves interpolated
# linearly between their packets (prefixes end at whole packets, whose
# steps would otherwise decide the comparison), then the bytes the stream
# with precincts needs for the PSNR the other reaches there. PSNR is
# `meshwave rd`'s: vertex PSNR against the remesh both streams code, peak =
# its bounding-box diagonal (the coding's cost alone; the remesh's own
# distance to the original is the same in both).
#
# Usage: bench/precinct_cost.sh [BUILD_DIR]
#   MESHES="a.ply b.obj"   other meshes (default: the shared ones)
#   PRECINCT_ARGS="..."    the precinct settings measured (default: none,
#                          i.e. the encoder's defaults)
#   CSV_DIR=dir            keep the curves there (and reuse those present)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
meshes=$(shared_meshes)
if [[ -n ${CSV_DIR:-} ]]; then
  tmp=$CSV_DIR
  mkdir -p "$tmp"
else
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
fi
printf '%-26s %9s %9s %7s  %s\n' mesh bytes_0 bytes_p 'size' \
  'at 5, 10, 25, 50, 90 % of bytes_0: PSNR without / with precincts (dB) [bytes with precincts for the same PSNR]'
for mesh in $meshes; do
  name=$(basename "${mesh%.*}")
  if [[ ! -s $tmp/$name.0.csv ]]; then
    echo "$name: rd without precincts" >&2
    "$cli" rd --coders 3xc --precinct-size 0 --csv "$tmp/$name.0.csv" "$mesh" > /dev/null
  fi
  if [[ ! -s $tmp/$name.p.csv ]]; then
    echo "$name: rd with precincts ${PRECINCT_ARGS:-(defaults)}" >&2
    # shellcheck disable=SC2086
    "$cli" rd --coders 3xc ${PRECINCT_ARGS:-} --csv "$tmp/$name.p.csv" "$mesh" > /dev/null
  fi
  python3 - "$name" "$tmp/$name.0.csv" "$tmp/$name.p.csv" << 'PY'
import csv, sys
name, a, b = sys.argv[1:]
def curve(path):
    rows = [r for r in csv.DictReader(open(path))]
    return [(int(r["bytes_total"]), float(r["psnr_db"])) for r in rows]
def interpolate(curve, x, at, to):
    # Linear between the points around coordinate `at` = x (0: bytes,
    # 1: PSNR); None past the curve's end, the first point before its start.
    prev = None
    for point in curve:
        if point[at] >= x:
            if prev is None:
                return point[to]
            if point[at] == prev[at]:
                return point[to]
            return prev[to] + (point[to] - prev[to]) * (x - prev[at]) / (point[at] - prev[at])
        prev = point
    return None
def psnr_at(curve, budget):
    # Before the first packet (the header alone is more): no PSNR.
    return None if budget < curve[0][0] else interpolate(curve, budget, 0, 1)
def bytes_for(curve, psnr):
    return interpolate(curve, psnr, 1, 0)
c0, cp = curve(a), curve(b)
full0, fullp = c0[-1][0], cp[-1][0]
cells = []
for share in (0.05, 0.10, 0.25, 0.50, 0.90):
    budget = share * full0
    p0, pp = psnr_at(c0, budget), psnr_at(cp, budget)
    if p0 is None or pp is None:
        cells.append("-")
        continue
    need = bytes_for(cp, p0)
    extra = f"{100 * (need - budget) / budget:+.1f}%" if need else "-"
    cells.append(f"{p0:.2f}/{pp:.2f} ({pp - p0:+.2f}) [{extra}]")
print(f"{name:<26} {full0:9d} {fullp:9d} {100 * (fullp - full0) / full0:+6.2f}%  " + "  ".join(cells))
PY
done
