#!/usr/bin/env bash
# Installs web/'s pinned npm packages (package-lock.json) into WORK_DIR with
# `npm ci`, only when the lockfile changed since the last install there, so
# a second run costs a file comparison. Prints WORK_DIR/node_modules.
# Used by the browser test, the glTF validation test, the vendored-three.js
# check and bench/viewer_first_mesh.sh; node_modules never lands in the repo.
#
# Usage: web/npm_ci.sh WORK_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?usage: npm_ci.sh WORK_DIR}
command -v npm > /dev/null || { echo "npm_ci.sh: npm not found (bash deploy/install-deps.sh)" >&2; exit 1; }
mkdir -p "$work"
if ! cmp -s "$here/package-lock.json" "$work/package-lock.json" || [[ ! -d $work/node_modules ]]; then
  rm -rf "$work/node_modules"
  cp "$here/package.json" "$here/package-lock.json" "$work/"
  (cd "$work" && npm ci --no-audit --no-fund --loglevel=error >&2)
fi
echo "$work/node_modules"
