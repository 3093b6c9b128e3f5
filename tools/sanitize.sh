#!/usr/bin/env bash
# Sanitizer stages (docs/RELIABILITY.md, "Sanitizers"), run by tools/test.sh
# (and so by .ci/run) after the Release stage. Two extra builds, kept small:
# -O1 without debug information, only the targets the suites below need,
# tests by ctest label two at a time.
#   asan: clang, ASan + UBSan with libFuzzer's coverage (-DMESHWAVE_FUZZ=ON,
#     build-asan): the codec's core, mesh I/O, entropy, stream, wavelet,
#     metrics and remeshing suites,
#     the server (unit, HTTP, WebSocket), the client (unit, end to end), the
#     fault and abuse tests, every fuzz replay (seeds + regression
#     corpus) and a 10-second libFuzzer run of every target. The servers and CLIs these tests start are ASan builds too.
#     The same build is a fuzzing build: bench/fuzz_run.sh runs its targets.
#   tsan: clang, TSan (build-tsan): the server's concurrency tests, i.e. the
#     HTTP and WebSocket integration suites and the fault and abuse tests,
#     whose meshwave-server processes (2 io threads) are TSan builds; the
#     core and stream suites (Deferred, DeferredSequence, ParallelFor, the
#     decoder's set-up threads).
# Both stages build with clang in unity batches (tools/build_flags.sh) and
# without the WebAssembly module; the Release stage is gcc's.
# Left out for time: the analysis and CLI suites (the CLI's code is the
# libraries' that the suites above run, plus argument parsing), and under
# ASan the long remesh and fidelity runs on shared meshes and the
# thread-count determinism runs (asan_excluded_tests in
# tools/sanitize_targets.sh; the Release stage runs them).
# A report from any process (test, server, CLI) fails the stage: the
# sanitizers write them to BUILD/sanitizer-reports/, printed here.
# Usage: bash tools/sanitize.sh [asan|tsan|all]  (default all)
set -euo pipefail
cd "$(dirname "$0")/.."
stage=${1:-all}
jobs=${SANITIZE_JOBS:-2}
source tools/sanitize_targets.sh
bash deploy/install-deps.sh
source tools/compiler_cache.sh
source tools/build_flags.sh
if ! command -v clang++ > /dev/null; then
  echo "sanitize: the sanitizer stages need clang (apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
# Build type flags: -O1 (sanitizers' advice for speed with usable reports),
# no -g (half the compile time; reports still name functions).
# A missing shared mesh fails or skips as tools/build_flags.sh decides.
# No WebAssembly decoder: the Release stage builds and tests it.
flags=(-G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"
       -DMESHWAVE_WASM=OFF "${ci_build_flags[@]}")
[[ -n ${CMAKE_CXX_COMPILER_LAUNCHER:-} ]] &&
  flags+=(-DCMAKE_CXX_COMPILER_LAUNCHER="$CMAKE_CXX_COMPILER_LAUNCHER")

# run_suites BUILD_DIR LABEL_REGEX [EXCLUDE_REGEX]: ctest by label; fails on
# a failed test or on any sanitizer report left by a process the tests started.
run_suites() {
  local dir=$1 labels=$2 reports=$1/sanitizer-reports
  local exclude=()
  [[ -n ${3:-} ]] && exclude=(-E "$3")
  rm -rf "$reports" && mkdir -p "$reports"
  local rc=0
  ctest --test-dir "$dir" -j"$jobs" -L "$labels" "${exclude[@]}" --output-on-failure --timeout 900 || rc=1
  if compgen -G "$reports/*" > /dev/null; then
    echo "sanitizer reports in $reports:"
    for f in "$reports"/*; do echo "== $f"; head -80 "$f"; done
    rc=1
  fi
  return $rc
}

if [[ $stage == all || $stage == asan ]]; then
  suites=("${asan_suites[@]}")
  fuzz=("${fuzz_targets[@]}")
  dir=build-asan
  start=$SECONDS
  cmake -S . -B $dir "${flags[@]}" -DCMAKE_CXX_COMPILER=clang++ -DMESHWAVE_FUZZ=ON
  cmake --build $dir -j"$jobs" --target "${suites[@]}" "${fuzz[@]}"
  built=$SECONDS
  export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:strict_string_checks=1:log_path=$PWD/$dir/sanitizer-reports/asan
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:log_path=$PWD/$dir/sanitizer-reports/ubsan
  labels="^($(IFS='|'; echo "${suites[*]}")|fuzz_replay|fuzz_short)\$"
  run_suites $dir "$labels" "^($(IFS='|'; echo "${asan_excluded_tests[*]}"))"
  unset ASAN_OPTIONS UBSAN_OPTIONS
  echo "sanitizers: ASan + UBSan passed (build $((built - start)) s, tests $((SECONDS - built)) s)"
fi

if [[ $stage == all || $stage == tsan ]]; then
  suites=("${tsan_suites[@]}")
  dir=build-tsan
  start=$SECONDS
  cmake -S . -B $dir "${flags[@]}" -DCMAKE_CXX_COMPILER=clang++ -DMESHWAVE_SANITIZE=thread
  cmake --build $dir -j"$jobs" --target "${suites[@]}"
  built=$SECONDS
  export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:log_path=$PWD/$dir/sanitizer-reports/tsan
  run_suites $dir "^($(IFS='|'; echo "${suites[*]}"))\$"
  unset TSAN_OPTIONS
  echo "sanitizers: TSan passed (build $((built - start)) s, tests $((SECONDS - built)) s)"
fi
