#!/bin/sh
# A decoder-only install exposes the decoder and nothing else: the source
# tree configured with MESHWAVE_DECODER_ONLY, built and installed to a
# temporary prefix, holds exactly the decoder's public headers
# (codec/include/decoder/meshwave), each of which compiles on its own with
# only that prefix and Eigen, and libmeshwave_decoder.a alone; and
# docs/client-example, built against it with find_package(meshwave),
# decodes a stream.
#   decoder_install_test.sh SOURCE_DIR CMAKE STREAM.mwv
set -eu
src=$1
cmake=$2
stream=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
log=$work/log.txt
run() {
  if ! "$@" >>"$log" 2>&1; then
    echo "FAIL: $*"
    tail -40 "$log"
    exit 1
  fi
}
run "$cmake" -S "$src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DMESHWAVE_DECODER_ONLY=ON -DMESHWAVE_TESTS=OFF -DMESHWAVE_PCH=OFF
run "$cmake" --build "$work/build" --parallel 2
run "$cmake" --install "$work/build" --prefix "$work/prefix"

status=0
expected=$(cd "$src/codec/include/decoder" && find meshwave -name '*.h' | sort)
installed=$(cd "$work/prefix/include" && find . -type f | sed 's#^\./##' | sort)
if [ "$installed" != "$expected" ]; then
  echo "FAIL: the installed headers are not the decoder's:"
  printf '%s\n' "$installed" > "$work/installed"
  printf '%s\n' "$expected" > "$work/expected"
  diff "$work/expected" "$work/installed" || true
  status=1
fi
for h in encoder.h remesh.h analysis.h metrics.h region_order.h mesh_io.h stream_units.h \
         region_text.h client/session.h; do
  if [ -e "$work/prefix/include/meshwave/$h" ]; then
    echo "FAIL: meshwave/$h is installed"
    status=1
  fi
done
libs=$(cd "$work/prefix/lib" && find . -name '*.a' | sed 's#^\./##' | sort | tr '\n' ' ')
if [ "$libs" != "libmeshwave_decoder.a " ]; then
  echo "FAIL: the installed libraries are '$libs', not libmeshwave_decoder.a alone"
  status=1
fi
# Each header stands alone: what it includes is installed beside it.
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3)
for h in $expected; do
  if ! printf '#include "%s"\n' "$h" |
      c++ -std=c++20 -fsyntax-only -I"$work/prefix/include" $eigen -x c++ - \
      >>"$log" 2>&1; then
    echo "FAIL: $h does not compile with the decoder-only install alone"
    status=1
  fi
done
run "$cmake" -S "$src/docs/client-example" -B "$work/example" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix"
run "$cmake" --build "$work/example" --parallel 2
if [ -e "$work/example/fetch_example" ]; then
  echo "FAIL: the client example was built against a decoder-only install"
  status=1
fi
run "$work/example/decode_example" "$stream" 100000 "$work/decoded.ply"
if ! grep -q '34 vertices, 64 faces' "$log"; then
  echo "FAIL: decode_example did not decode the stream"
  tail -5 "$log"
  status=1
fi
[ $status -eq 0 ] && echo "ok: $(echo "$expected" | wc -l) decoder headers installed, nothing else"
exit $status
