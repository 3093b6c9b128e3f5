#!/usr/bin/env bash
# Long fuzzing sessions: runs each libFuzzer target of tests/fuzz for a
# bounded time, one at a time under `nice -n 19`, and appends what it did
# (executions, coverage, crashes) to bench/fuzz_runs.tsv, the ledger
# docs/RELIABILITY.md sums.
#
# Usage: bench/fuzz_run.sh [SECONDS_PER_TARGET] [TARGET...]   (default 600, all)
#   Needs a build configured with -DMESHWAVE_FUZZ=ON, by default build-fuzz:
#     cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DMESHWAVE_FUZZ=ON
#     cmake --build build-fuzz --target <targets>
# Environment: FUZZ_BUILD=DIR (default build-fuzz), FUZZ_JOBS=N (parallel
#   libFuzzer jobs per target, default 1), FUZZ_NICE=N (default 19: the
#   machine's other users come first), FUZZ_MAX_LEN=N (libFuzzer -max_len),
#   FUZZ_TIMEOUT=S (default 120: libFuzzer's -timeout is wall-clock time, and
#   a process at nice 19 on a loaded machine can wait seconds for a core; at
#   -timeout=10 two inputs that run in 3 and 29 ms were reported as hangs),
#   FUZZ_ENTROPIC=1 (libFuzzer's entropic power schedule; off by default:
#   with a grown corpus its UpdateFeatureFrequency took 68 % of packet_fuzz's
#   time, 3,900 against 25,300 executions in 10 s with -entropic=0),
#   FUZZ_RUNS=N (stop after N executions, libFuzzer -runs, even before
#   SECONDS: to top a target up to a total).
#
# Each target fuzzes into its working corpus FUZZ_BUILD/tests/fuzz/work/T
# (kept between runs, so coverage accumulates), seeded from
# tests/fuzz/seeds/T and the regression corpus tests/fuzz/corpus/T. A
# crash, leak, timeout or out-of-memory input is saved in
# FUZZ_BUILD/tests/fuzz/artifacts/T/: fix the bug, then copy the input to
# tests/fuzz/corpus/T/ so that fuzz_replay_T replays it in every build.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-600}
shift || true
build=${FUZZ_BUILD:-$root/build-fuzz}
[[ $build = /* ]] || build=$root/$build
jobs=${FUZZ_JOBS:-1}
niceness=${FUZZ_NICE:-19}
all=(ply_reader_fuzz obj_reader_fuzz off_reader_fuzz container_fuzz packet_fuzz
     decoder_order_fuzz http_request_fuzz ws_message_fuzz stream_splitter_fuzz
     ws_server_message_fuzz local_state_fuzz region_fuzz gltf_asset_fuzz obj_asset_fuzz
     image_decoder_fuzz multipart_form_fuzz)
targets=("$@")
((${#targets[@]})) || targets=("${all[@]}")
ledger=$root/bench/fuzz_runs.tsv
[[ -f $ledger ]] || printf 'date\ttarget\tseconds\texecutions\texec_per_s\tcoverage\tcorpus\tresult\n' > "$ledger"

dict_of() {
  case $1 in
    ply_reader_fuzz) echo ply.dict ;; obj_reader_fuzz) echo obj.dict ;;
    off_reader_fuzz) echo off.dict ;; container_fuzz) echo container.dict ;;
    http_request_fuzz) echo http.dict ;; ws_message_fuzz) echo ws.dict ;;
    gltf_asset_fuzz) echo gltf.dict ;; obj_asset_fuzz) echo obj_asset.dict ;;
  esac
}

for t in "${targets[@]}"; do
  bin=$build/tests/fuzz/$t
  if [[ ! -x $bin ]]; then echo "fuzz_run: no $bin, skipped" >&2; continue; fi
  work=$build/tests/fuzz/work/$t
  artifacts=$build/tests/fuzz/artifacts/$t
  mkdir -p "$work" "$artifacts"
  args=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout="${FUZZ_TIMEOUT:-120}" -print_final_stats=1
        -entropic="${FUZZ_ENTROPIC:-0}"
        -artifact_prefix="$artifacts/")
  [[ -n ${FUZZ_MAX_LEN:-} ]] && args+=(-max_len="$FUZZ_MAX_LEN")
  [[ -n ${FUZZ_RUNS:-} ]] && args+=(-runs="$FUZZ_RUNS")
  d=$(dict_of "$t")
  [[ -n $d && -f $root/tests/fuzz/dict/$d ]] && args+=(-dict="$root/tests/fuzz/dict/$d")
  corpora=("$work")
  for c in "$root/tests/fuzz/seeds/$t" "$root/tests/fuzz/corpus/$t"; do
    [[ -d $c ]] && corpora+=("$c")
  done
  log=$build/tests/fuzz/$t.log
  before=$(find "$artifacts" -type f | wc -l)
  echo "fuzz_run: $t for ${seconds}s" >&2
  started=$SECONDS
  set +e
  if ((jobs > 1)); then
    nice -n "$niceness" "$bin" "${args[@]}" -jobs="$jobs" -workers="$jobs" "${corpora[@]}" > "$log" 2>&1
    cat "$build"/tests/fuzz/fuzz-*.log >> "$log" 2>/dev/null; rm -f "$build"/tests/fuzz/fuzz-*.log
  else
    nice -n "$niceness" "$bin" "${args[@]}" "${corpora[@]}" > "$log" 2>&1
  fi
  rc=$?
  set -e
  elapsed=$((SECONDS - started))
  execs=$(grep -h '^stat::number_of_executed_units:' "$log" | awk '{s += $2} END {print s + 0}')
  rate=$(grep -h '^stat::average_exec_per_sec:' "$log" | awk '{s += $2} END {print s + 0}')
  cov=$(grep -ho 'cov: [0-9]*' "$log" | tail -1 | awk '{print $2}')
  corpus=$(find "$work" -type f | wc -l)
  after=$(find "$artifacts" -type f | wc -l)
  result=ok
  ((rc == 0)) || result="exit $rc"
  ((after > before)) && result="$result; new artifact: $(ls -t "$artifacts" | head -1)"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$t" "$elapsed" "$execs" "$rate" \
    "${cov:-?}" "$corpus" "$result" | tee -a "$ledger"
done
