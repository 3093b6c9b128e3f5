#!/usr/bin/env bash
# Screen-space-error requests against the uniform rd order (issue 39): each
# shared mesh encoded (`meshwave encode`, default settings plus
# $ENCODE_ARGS), then `meshwave view-rd` on the stream: along an orbit (8
# cameras) and a zoom onto a detail (5 cameras), 1280x720 at 45 degrees,
# the bytes the view requests with screen_error 1 and 4 px bring (each
# camera continuing from what the ones before brought), the largest error
# any camera then shows, and the shortest rd prefix that brings every
# camera of the path within the same tolerance.
#
# Usage: bench/view_table.sh [BUILD_DIR]
#   MESHES="a.ply b.obj"   other meshes (default: the shared ones)
#   ENCODE_ARGS="..."      e.g. "--precinct-size 1024"
#   TOLERANCES=1,4         pixels
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
meshes=$(shared_meshes)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "# meshwave view-rd, encode options: ${ENCODE_ARGS:-(defaults)}; $(date -u +%F)"
for mesh in $meshes; do
  name=$(basename "${mesh%.*}")
  echo "$name: encoding" >&2
  # shellcheck disable=SC2086
  "$cli" encode ${ENCODE_ARGS:-} "$mesh" "$tmp/$name.mwv" > /dev/null 2>&1
  "$cli" view-rd --tolerances "${TOLERANCES:-1,4}" "$tmp/$name.mwv"
done
