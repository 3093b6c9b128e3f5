#!/usr/bin/env bash
# Checks that the three.js files vendored under web/viewer/vendor/three are
# byte for byte those of the three package web/package-lock.json pins (the
# viewer ships them so that it works offline from the server alone).
# After `npm install --save-exact three@X` in web/, `check_vendor.sh --update`
# copies the new files in.
#
# Usage: web/check_vendor.sh WORK_DIR [--update]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?usage: check_vendor.sh WORK_DIR [--update]}
modules=$(bash "$here/npm_ci.sh" "$work")
vendor=$here/viewer/vendor/three
# vendored path : path in the npm package
files=(
  three.module.js:build/three.module.js
  three.core.js:build/three.core.js
  LICENSE:LICENSE
  addons/controls/OrbitControls.js:examples/jsm/controls/OrbitControls.js
)
locked=$(node -e 'console.log(require(process.argv[1]).packages["node_modules/three"].version)' \
  "$here/package-lock.json")
installed=$(node -e 'console.log(require(process.argv[1]).version)' "$modules/three/package.json")
[[ $locked == "$installed" ]] || { echo "FAIL: three $installed installed, $locked locked" >&2; exit 1; }
status=0
for f in "${files[@]}"; do
  ours=$vendor/${f%%:*} theirs=$modules/three/${f#*:}
  if [[ ${2:-} == --update ]]; then
    mkdir -p "$(dirname "$ours")" && cp "$theirs" "$ours"
  elif ! cmp -s "$ours" "$theirs"; then
    echo "FAIL: $ours differs from three@$locked's ${f#*:}" >&2
    status=1
  fi
done
# Nothing else under vendor/: every shipped file is checked.
extra=$(cd "$vendor" && find . -type f | sed 's|^\./||' | sort)
want=$(for f in "${files[@]}"; do echo "${f%%:*}"; done | sort)
if [[ $extra != "$want" ]]; then
  echo "FAIL: vendor/three holds files this check does not know:" >&2
  diff <(echo "$want") <(echo "$extra") >&2 || true
  status=1
fi
((status == 0)) && echo "vendored three.js equals three@$locked (${#files[@]} files)"
exit $status
