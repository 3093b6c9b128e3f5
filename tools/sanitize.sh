#!/usr/bin/env bash
# Sanitizer stages (docs/RELIABILITY.md), NOT part of .ci/run: on the 2-core
# machine a plain CI run already takes 10+ minutes and these two extra
# builds would take it well past the 20-minute budget.
#   ASan + UBSan (build-asan): the suites that take untrusted bytes or run
#     the server and client end to end, and every fuzz replay.
#   TSan (build-tsan): the server HTTP tests and the fault and abuse tests,
#     whose server processes are TSan builds too (a race makes them exit 66
#     instead of 0, which the tests check).
# Left out for time: the remeshing, wavelet, metrics, analysis and CLI
# suites (their inputs are our own meshes; the fuzz replays cover the
# readers). Usage: bash tools/sanitize.sh [asan|tsan|all]  (default all)
set -euo pipefail
cd "$(dirname "$0")/.."
stage=${1:-all}
bash deploy/install-deps.sh

# Runs test commands two at a time; prints the log of any that fails.
run_tests() {
  local dir=$1 failed=0 pids=() names=()
  shift
  for cmd in "$@"; do
    local name=${cmd%% *}
    name=${name##*/}
    ( cd "$dir" && timeout 900 bash -c "$cmd" > "$dir/$name.sanitizer.log" 2>&1 ) &
    pids+=($!) names+=("$name")
    if ((${#pids[@]} == 2)); then
      wait "${pids[0]}" || { failed=1; echo "FAILED: ${names[0]}"; tail -60 "$dir/${names[0]}.sanitizer.log"; }
      pids=("${pids[1]}") names=("${names[1]}")
    fi
  done
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}" || { failed=1; echo "FAILED: ${names[$i]}"; tail -60 "$dir/${names[$i]}.sanitizer.log"; }
  done
  return $failed
}

if [[ $stage == all || $stage == asan ]]; then
  fuzz=(ply_reader_fuzz obj_reader_fuzz off_reader_fuzz container_fuzz packet_fuzz
        decoder_order_fuzz http_request_fuzz)
  asan=build-asan
  cmake -S . -B $asan -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHWAVE_WERROR=ON \
    -DMESHWAVE_SANITIZE="address;undefined"
  cmake --build $asan -j2 --target core_test mesh_test stream_test entropy_test server_test \
    server_http_test client_test client_e2e_test reliability_test "${fuzz[@]/%/_replay}"
  export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  commands=()
  for t in core_test mesh_test stream_test entropy_test server_test server_http_test client_test \
           client_e2e_test reliability_test; do
    d=tests; [[ $t == reliability_test ]] && d=tests/reliability
    commands+=("$PWD/$asan/$d/$t --gtest_brief=1")
  done
  for f in "${fuzz[@]}"; do
    commands+=("$PWD/$asan/tests/fuzz/${f}_replay $PWD/tests/fuzz/seeds/$f $PWD/tests/fuzz/corpus/$f")
  done
  run_tests "$PWD/$asan" "${commands[@]}"
  echo "sanitizers: ASan + UBSan passed (${#commands[@]} test programs)"
fi

if [[ $stage == all || $stage == tsan ]]; then
  tsan=build-tsan
  cmake -S . -B $tsan -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHWAVE_WERROR=ON -DMESHWAVE_SANITIZE=thread
  cmake --build $tsan -j2 --target server_http_test reliability_test
  export TSAN_OPTIONS=halt_on_error=0:second_deadlock_stack=1
  run_tests "$PWD/$tsan" "$PWD/$tsan/tests/server_http_test --gtest_brief=1" \
    "$PWD/$tsan/tests/reliability/reliability_test --gtest_brief=1"
  echo "sanitizers: TSan passed"
fi
