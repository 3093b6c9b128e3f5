#!/usr/bin/env bash
# Runs viewer_test.mjs (or TEST, another browser test taking the same
# options: viewer_region_test.mjs): npm packages from web/package-lock.json
# (web/npm_ci.sh, a no-op when already installed), screenshots into
# WORK_DIR/artefacts.
# Exit 77 (ctest: skipped) without Chromium or without the decoder module.
#
# Usage: run_viewer_test.sh WORK_DIR SERVER_BINARY CLI_BINARY DECODER_JS SAMPLE_MESH [TEST [OPTION...]]
#   (OPTIONs go to TEST as they are, e.g. --textured FILE)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?work dir} server=${2:?server} cli=${3:?cli} decoder=${4:-} mesh=${5:?sample mesh}
test=${6:-viewer_test.mjs}
shift $(($# < 6 ? $# : 6))
if [[ ! -x /usr/bin/chromium ]]; then
  echo "SKIP: /usr/bin/chromium not installed (bash deploy/install-deps.sh installs Debian's chromium)"
  exit 77
fi
if [[ -z $decoder || ! -f $decoder ]]; then
  echo "SKIP: the WebAssembly decoder module is not built (${decoder:-no path given}): configure with" \
    "-DMESHWAVE_DECODER_JS=PATH/meshwave_decoder.js"
  exit 77
fi
command -v node > /dev/null || { echo "FAIL: node not found (bash deploy/install-deps.sh)" >&2; exit 1; }
modules=$(bash "$here/../../web/npm_ci.sh" "$work/npm")
exec node "$here/$test" --server "$server" --cli "$cli" --decoder "$decoder" \
  --viewer "$here/../../web/viewer" --mesh "$mesh" --node-modules "$modules" \
  --artefacts "$work/artefacts" "$@"
