#!/usr/bin/env bash
# The main job: installs dependencies, builds, and runs the meshwave CLI on
# the shipped sample mesh (describe it, subdivide it into a semi-regular mesh,
# detect the levels back, and compare the result with the original).
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
