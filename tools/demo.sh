#!/usr/bin/env bash
# The main job: installs what building needs (deploy/install-deps.sh build:
# no test tools, no browser, no emscripten), builds the CLI and the server
# (the viewer's WebAssembly decoder comes built, web/dist), runs the meshwave CLI on the
# shipped sample meshes (describe, subdivide, encode, decode at budgets,
# compare; a textured glTF described, encoded and decoded), then starts
# meshwave-server on an embedded default catalog (SQLite, in a temporary
# directory) holding the sample meshes (a textured and a coloured one among
# them), and streams
# one with the client: a fetch at a budget, then two refinements that pull
# only the next packets. It prints the browser viewer's URL
# (http://127.0.0.1:PORT/viewer/) and, run from a terminal, keeps the server
# up until Enter.
#   DEMO_BUILD_DIR=DIR  use DIR's programs as they are: no install, no build
#                       (the test suite's demo_test runs it so)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${DEMO_BUILD_DIR:-build}
if [[ -z ${DEMO_BUILD_DIR:-} ]]; then
  bash deploy/install-deps.sh build
  # The compiler cache when there is one (a machine that has run the
  # tests); unity builds, as the tests build (tools/build_flags.sh): the
  # headers most of the time goes into are parsed once per batch. No tests
  # and, even where emscripten is installed, the shipped decoder module.
  source tools/compiler_cache.sh
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHWAVE_TESTS=OFF \
    -DMESHWAVE_WASM=OFF -DCMAKE_UNITY_BUILD=ON -DMESHWAVE_PCH=OFF
  cmake --build build -j2 --target meshwave meshwave-server
fi
cli=$build/tools/meshwave/meshwave
server=$build/server/meshwave-server
out=$(mktemp -d)
server_pid=
cleanup() {
  if [[ -n $server_pid ]]; then kill "$server_pid" 2> /dev/null || true; wait "$server_pid" 2> /dev/null || true; fi
  rm -rf "$out"
}
trap cleanup EXIT

echo "== meshwave info data/elephant.off"
$cli info data/elephant.off
echo
echo "== meshwave subdivide data/elephant.off --levels 2 --scheme butterfly"
$cli subdivide data/elephant.off "$out/elephant_sr2.ply" --levels 2 --scheme butterfly
echo
echo "== meshwave info (the subdivided mesh: 2 levels detected)"
$cli info "$out/elephant_sr2.ply"
echo
echo "== meshwave compare data/elephant.off elephant_sr2.ply"
$cli compare data/elephant.off "$out/elephant_sr2.ply"
echo
echo "== meshwave encode data/holes.off (semi-regular, 2 levels) into a 3xC stream"
$cli encode data/holes.off "$out/holes.mwv"
for budget in 6000 8000 10000; do
  echo
  echo "== meshwave decode holes.mwv --budget $budget"
  $cli decode "$out/holes.mwv" "$out/holes_$budget.ply" --budget "$budget"
  $cli compare data/holes.off "$out/holes_$budget.ply" | grep -E "vertex (matching|rms)"
done
echo
echo "== meshwave decode holes.mwv holes.glb (glTF 2.0, by the extension)"
$cli decode "$out/holes.mwv" "$out/holes.glb" --budget 8000
echo
echo "== meshwave decode holes.mwv --order resolution --max-level 1 (a smaller mesh)"
$cli decode "$out/holes.mwv" "$out/holes_level1.ply" --order resolution --max-level 1
echo
echo "== meshwave info data/textured/ring.glb (UVs, colours, materials and a texture)"
$cli info data/textured/ring.glb
echo
echo "== meshwave encode data/textured/ring.glb (its materials and texture baked onto the remesh)"
$cli encode data/textured/ring.glb "$out/ring.mwv"
echo
echo "== meshwave decode ring.mwv --budget 4000 ring.glb (a textured glTF of the prefix)"
$cli decode "$out/ring.mwv" "$out/ring.glb" --budget 4000

echo
echo "== meshwave-server ingest: the sample meshes into a new catalog (elephant.off is remeshed;"
echo "   the die with its .mtl and texture, the vertex-coloured ball)"
$server ingest --catalog "$out/catalog" data/elephant.off data/holes.off \
  data/textured/die.obj data/textured/hue_ball.ply | tee "$out/ingest.txt"
# The id opens the line that names the file (grep -E: Debian's awk, mawk,
# has no {12}).
id=$(grep -E '^[0-9a-f]{12} .*elephant\.off' "$out/ingest.txt" | head -n 1 | cut -d ' ' -f 1)
die=$(grep -E '^[0-9a-f]{12} .*die\.obj' "$out/ingest.txt" | head -n 1 | cut -d ' ' -f 1)
if [[ -z $id || -z $die ]]; then
  echo "demo: the ingest printed no id for elephant.off or die.obj" >&2
  exit 1
fi
echo
echo "== meshwave-server on 127.0.0.1 (a free port)"
$server --catalog "$out/catalog" --listen 127.0.0.1:0 --port-file "$out/port" > "$out/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do [[ -s $out/port ]] && break; sleep 0.1; done
[[ -s $out/port ]] || { cat "$out/server.log"; echo "server did not start" >&2; exit 1; }
url=http://127.0.0.1:$(cat "$out/port")
echo "serving at $url"
echo "the viewer, on the textured die: open $url/viewer/?mesh=$die in a browser"
echo "(catalog, streaming, refine; 'hue_ball' has vertex colours)"
echo
echo "== meshwave catalog $url"
$cli catalog "$url"
echo
echo "== meshwave fetch: the elephant at a 3000-byte budget, rd order"
$cli fetch "$url/v1/meshes/$id" --budget 3000 --order rd --state "$out/e.mwv" \
  --out "$out/e.ply" --reference data/elephant.off
for more in 2000 4000; do
  echo
  echo "== meshwave refine: $more more bytes (only the next packets)"
  $cli refine "$out/e.mwv" --more "$more" --reference data/elephant.off
done
echo
if [[ -t 0 ]]; then
  echo "== the viewer is at $url/viewer/?mesh=$die (the textured die) — press Enter to stop the server"
  read -r
fi
echo "== done: the server stops, the temporary catalog is removed"
