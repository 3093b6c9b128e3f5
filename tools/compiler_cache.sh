# Sourced by tools/test.sh and tools/sanitize.sh: builds go through ccache
# when it is installed (deploy/install-deps.sh installs it), so a clean
# clone on a machine that has built meshwave before compiles only what
# changed. Objects are keyed by paths relative to the clone
# (CCACHE_BASEDIR), so clones in other folders share them; the sloppiness
# lets clang's precompiled headers be cached (they are otherwise
# uncacheable). A cold cache costs a few percent over no cache.
# CCACHE_DISABLE=1 turns it off; an explicit CMAKE_CXX_COMPILER_LAUNCHER wins.
if [[ -z ${CMAKE_CXX_COMPILER_LAUNCHER:-} && ${CCACHE_DISABLE:-0} != 1 ]] &&
  command -v ccache > /dev/null; then
  export CMAKE_CXX_COMPILER_LAUNCHER=ccache
  export CCACHE_BASEDIR=$PWD
  export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
  export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-20G}
fi
