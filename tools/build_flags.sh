# Sourced by tools/test.sh and tools/sanitize.sh: how the test command's
# builds compile, for time (docs/BENCHMARKS.md, "Build time").
# Unity builds: each target compiles its files in batches of eight, so the
# headers that take most of a file's time (Eigen, Asio, Beast, protobuf,
# GoogleTest) are parsed once a batch rather than once a file. Precompiled
# headers off: a unity batch already shares its headers, and a clang
# precompiled header names this clone's paths, which would keep the
# compiler cache from reusing objects between clones in other folders.
# MESHWAVE_UNITY=0 builds file by file (what a developer's plain cmake does).
ci_build_flags=()
if [[ ${MESHWAVE_UNITY:-1} != 0 ]]; then
  ci_build_flags+=(-DCMAKE_UNITY_BUILD=ON -DMESHWAVE_PCH=OFF)
fi

# The shared development meshes (../shared/data/meshes): a clone with nothing
# beside it skips the tests that need them, one line each; where shared/ is
# beside the clone (CI's layout) or CI is set, a missing mesh fails the test
# instead, so nothing is silently skipped there.
if [[ -n ${CI:-} || -d ../shared ]]; then
  ci_build_flags+=(-DMESHWAVE_REQUIRE_SHARED_MESHES=ON)
else
  ci_build_flags+=(-DMESHWAVE_REQUIRE_SHARED_MESHES=OFF)
  echo "build: no ../shared beside the clone: the tests that need its meshes will be skipped" >&2
fi
