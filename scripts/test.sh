#!/usr/bin/env bash
# Build everything, tests included, and run every test: the README's test command and CI's.
#
# usage: scripts/test.sh [--release] [BUILD_DIR] [extra cmake args...]
#
# Default: the tests run under AddressSanitizer + UndefinedBehaviorSanitizer (clang, -O1 with
# line tables), in build-test/: every test also checks for memory errors, leaks and undefined
# behaviour. Installs what it needs (scripts/setup.sh, and clang with its sanitizer runtimes,
# scripts/install_clang.sh).
#   --release   the Release build of the main job instead (GCC, -O3, build/ by default): the
#               same tests without the sanitizers' checks, about twice as fast to run
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
release=0
if [ "${1:-}" = "--release" ]; then
  release=1
  shift
fi
if [ "$release" = 1 ]; then
  dir=${1:-$root/build}
  shift || true
  SONARLOOP_BUILD_ALL=1 "$root/scripts/build.sh" "$dir" "$@"
else
  dir=${1:-$root/build-test}
  shift || true
  "$root/scripts/install_clang.sh"
  # -O1 -g1: line tables for the reports, at half the compile time of -O2 -g (the libraries, the
  # code under test, are raised to -O2: cmake/SonarloopTargets.cmake)
  SONARLOOP_BUILD_ALL=1 "$root/scripts/build.sh" "$dir" -DSONARLOOP_SANITIZE=ON \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "$@"
  # a finding fails its test: leaks reported, UB stops the process, a stack for each report
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1 ${ASAN_OPTIONS:-}"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1 ${UBSAN_OPTIONS:-}"
fi
# one entry per core, and besides them the entries that mostly wait on real time ([realtime]
# cases, cmake/SonarloopTests.cmake: a "waits" slot of build/ctest_resources.json)
# (ctest reads the resource file from inside the test directory: the path must be absolute)
dir=$(cd "$dir" && pwd)
ctest --test-dir "$dir" --output-on-failure -j "$(( $(nproc) + 1 ))" \
  --resource-spec-file "$dir/ctest_resources.json"
