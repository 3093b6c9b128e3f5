#!/usr/bin/env bash
# The test command: installs dependencies, builds everything with warnings as
# errors, and runs the whole test suite. CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHWAVE_WERROR=ON
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2 --timeout 900
