#!/usr/bin/env bash
# The main job: installs dependencies, builds, and runs the meshwave CLI on
# the shipped sample meshes: describe, subdivide, detect the levels back,
# encode into an embedded stream, decode it whole and at byte budgets, and
# compare with the original. (The server and client come next; this script
# will then start the server and stream the sample mesh with the client.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2 --target meshwave
cli=build/tools/meshwave/meshwave
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "== meshwave info data/elephant.off"
$cli info data/elephant.off
echo
echo "== meshwave subdivide data/elephant.off --levels 2 --scheme butterfly"
$cli subdivide data/elephant.off "$out/elephant_sr2.ply" --levels 2 --scheme butterfly
echo
echo "== meshwave info (the subdivided mesh: 2 levels detected)"
$cli info "$out/elephant_sr2.ply"
echo
echo "== meshwave compare data/elephant.off elephant_sr2.ply"
$cli compare data/elephant.off "$out/elephant_sr2.ply"
echo
echo "== meshwave encode data/holes.off (semi-regular, 2 levels) into a 3xC stream"
$cli encode data/holes.off "$out/holes.mwv"
for budget in 6000 8000 10000; do
  echo
  echo "== meshwave decode holes.mwv --budget $budget"
  $cli decode "$out/holes.mwv" "$out/holes_$budget.ply" --budget "$budget"
  $cli compare data/holes.off "$out/holes_$budget.ply" | grep -E "vertex (matching|rms)"
done
echo
echo "== meshwave decode holes.mwv --order resolution --max-level 1 (a smaller mesh)"
$cli decode "$out/holes.mwv" "$out/holes_level1.ply" --order resolution --max-level 1
