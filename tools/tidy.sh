#!/usr/bin/env bash
# clang-tidy on the codec (.clang-tidy says which checks and why), every
# finding an error. The test command runs it on its Release build.
#
# Usage: tools/tidy.sh [BUILD_DIR]     (default: build; needs its
#   compile_commands.json, which every configure of this project writes)
# It reads the codec's sources as that build compiles them: file by file,
# or in the unity batches of the test command's build (tools/build_flags.sh),
# where bugprone-suspicious-include is off because a batch includes .cpp
# files by design.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
commands=$build/compile_commands.json
[[ -f $commands ]] || { echo "tidy: no $commands (configure the build first)" >&2; exit 1; }
command -v run-clang-tidy > /dev/null || {
  echo "tidy: run-clang-tidy is missing (apt-get install clang-tidy)" >&2; exit 1; }
if grep -q 'meshwave_codec.dir/Unity/' "$commands"; then
  files='meshwave_codec\.dir/Unity/.*\.cxx$'
  checks=(-checks=-bugprone-suspicious-include)
else
  files='codec/src/.*\.cpp$'
  checks=()
fi
start=$SECONDS
log=$build/clang-tidy.log
# run-clang-tidy 14 cannot pass -warnings-as-errors: a finding is any
# "warning:" or "error:" line it prints.
status=0
run-clang-tidy -p "$build" -j 2 -quiet "${checks[@]}" "$files" > "$log" 2>&1 || status=$?
findings=$(sed 's/\x1b\[[0-9;]*m//g' "$log" | grep -E '(warning|error): ' | sort -u || true)
if (( status != 0 )) || [[ -n $findings ]]; then
  echo "$findings" >&2
  echo "tidy: clang-tidy found the problems above (exit $status; full output: $log)" >&2
  exit 1
fi
echo "tidy: clang-tidy clean on the codec ($((SECONDS - start)) s)"
