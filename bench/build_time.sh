#!/usr/bin/env bash
# Build time of one CI stage's build from scratch, with or without
# precompiled headers (docs/BENCHMARKS.md, "Build time"): configures a fresh
# directory like tools/test.sh (release) or tools/sanitize.sh (asan, tsan)
# do, builds the same targets with -j2 and no compiler cache, and prints the
# wall time, the compile steps' seconds summed (from .ninja_log) and the
# slowest steps.
#
# Usage: bench/build_time.sh release|asan|tsan [pch|nopch] [BUILD_DIR]
#   default pch; BUILD_DIR default /tmp/meshwave-build-time-STAGE-PCH
#   (removed first).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
stage=${1:?usage: bench/build_time.sh release|asan|tsan [pch|nopch] [BUILD_DIR]}
pch=${2:-pch}
dir=${3:-/tmp/meshwave-build-time-$stage-$pch}
case $pch in pch) pch_flag=ON ;; nopch) pch_flag=OFF ;; *) echo "pch or nopch, not $pch" >&2; exit 2 ;; esac

source "$root/tools/sanitize_targets.sh"
sanitizer_flags=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG")
targets=()  # empty: everything
case $stage in
  release) flags=(-DCMAKE_BUILD_TYPE=Release -DMESHWAVE_WERROR=ON) ;;
  asan)
    flags=("${sanitizer_flags[@]}" -DCMAKE_CXX_COMPILER=clang++ -DMESHWAVE_FUZZ=ON)
    targets=("${asan_suites[@]}" "${fuzz_targets[@]}") ;;
  tsan)
    flags=("${sanitizer_flags[@]}" -DCMAKE_CXX_COMPILER=clang++ -DMESHWAVE_SANITIZE=thread)
    targets=("${tsan_suites[@]}") ;;
  *) echo "unknown stage $stage (release, asan, tsan)" >&2; exit 2 ;;
esac

rm -rf "$dir"
export CCACHE_DISABLE=1
unset CMAKE_CXX_COMPILER_LAUNCHER
cmake -S "$root" -B "$dir" -G Ninja "${flags[@]}" -DMESHWAVE_PCH=$pch_flag > "$dir.configure.log"
start=$(date +%s.%N)
if ((${#targets[@]})); then
  cmake --build "$dir" -j2 --target "${targets[@]}" > "$dir.build.log"
else
  cmake --build "$dir" -j2 > "$dir.build.log"
fi
end=$(date +%s.%N)
# .ninja_log: start ms, end ms, mtime, output, hash (one line per step).
awk -v stage="$stage" -v pch="$pch" -v start="$start" -v end="$end" '
  NR > 1 { t = ($2 - $1) / 1000; sum += t; n++; step[$4] = t }
  END {
    printf "%s %s: %d steps, wall %.0f s, compile steps summed %.0f s\n", stage, pch, n, end - start, sum
    for (s in step) printf "%8.1f %s\n", step[s], s | "sort -rn | head -8"
  }' "$dir/.ninja_log"
