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
