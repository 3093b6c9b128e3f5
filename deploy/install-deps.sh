#!/usr/bin/env bash
# Installs the Debian 12 packages meshwave needs. Safe to run again: it only
# calls apt-get when something is missing.
#
#   bash deploy/install-deps.sh          everything: build, tests, deployment tests
#   bash deploy/install-deps.sh build    only what building the programs needs
#                                        (the main job, tools/demo.sh: the viewer's
#                                        decoder comes built in web/dist)
#   bash deploy/install-deps.sh server   that and what the viewer's WebAssembly
#                                        decoder is built with (the Dockerfile's
#                                        build stage: the image serves /viewer/)
set -euo pipefail

build=(
  build-essential cmake ninja-build pkg-config
  libboost1.81-all-dev         # Asio, Beast, CRC
  libprotobuf-dev protobuf-compiler
  libeigen3-dev
  libspdlog-dev
  libcli11-dev
  libsqlite3-dev
  zlib1g-dev                   # PNG output of meshwave render
  libpq-dev                    # PostgreSQL catalog backend (libpq)
  libssl-dev                   # SHA-256 (content hashes), TLS
  libtinygltf-dev nlohmann-json3-dev   # glTF input (codec/src/asset: the header, compiled in)
  libpng-dev libturbojpeg0-dev libwebp-dev  # texture images of glTF and OBJ inputs
)
viewer=(
  emscripten nodejs            # web/build_decoder.sh: the decoder the viewer runs
)
test=(
  libgtest-dev libgmock-dev libbenchmark-dev
  postgresql                   # catalog tests and the replica test start their own server
  nginx-light                  # the replica test's load balancer and cache
  wrk                          # the upgrade test's HTTP load (tests/server/upgrade_test.cpp)
  docker-compose               # `docker-compose config`: compose file validation, no engine
  clang libclang-rt-14-dev     # the ASan + UBSan stage and the libFuzzer targets (tools/sanitize.sh)
  clang-tidy                   # tools/tidy.sh on the codec, in the Release stage
  ccache                       # tools/compiler_cache.sh: a clone rebuilds only what changed
  emscripten                   # the WebAssembly decoder's test under Node (tests/web)
  python3-websockets python3-protobuf  # tests/interop: the Python client written from the docs
  chromium                     # the viewer's browser test (tests/browser), headless
)
bench=(
  draco jq bc                  # bench/: Draco 1.5, the baseline, and the tables' arithmetic
  gltfpack webp libjpeg-turbo-progs libopenjp2-tools  # bench/texture_*.py: anchors and texture codecs
  wrk nginx-light              # bench/http_load.sh: the load generator and the nginx reference
  time                         # /usr/bin/time: wall time and peak memory (bench/ingest_scale.sh)
)

case "${1:-all}" in
  build) packages=("${build[@]}") ;;
  server) packages=("${build[@]}" "${viewer[@]}") ;;
  all) packages=("${build[@]}" "${viewer[@]}" "${test[@]}") ;;
  bench) packages=("${build[@]}" "${test[@]}" "${bench[@]}") ;;
  *) echo "usage: install-deps.sh [build|server|all|bench]" >&2; exit 2 ;;
esac

# Kubernetes manifest validation (tests/deploy/validate_manifests.sh), the
# viewer's browser test and the glTF validation run on Node.js; their npm
# packages are pinned by lockfiles and installed by the tests (web/npm_ci.sh). One from elsewhere (NodeSource's bundles npm) serves as well as
# Debian's, and Debian's npm would not install beside it.
if [[ ${1:-all} = all ]] && ! { command -v node && command -v npm; } > /dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all packages present"
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
# Debian's postgresql and nginx packages start their services on install
# where an init system runs; the tests start their own on free ports, so a
# system one is harmless, and in containers policy-rc.d keeps them off.
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
