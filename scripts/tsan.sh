#!/usr/bin/env bash
# The concurrent code under ThreadSanitizer (GCC): builds, with -fsanitize=thread, the tests of
# everything that runs threads (the list: SONARLOOP_TSAN_TESTS in tests/CMakeLists.txt; the only
# tests of this build) and the sonarloop binary; runs those tests, then the main job itself for
# 10 s of the default scenario as fast as possible, recorded (render workers, publisher, UDP,
# the recorders). A reported race fails it.
# Usage: scripts/tsan.sh [--build-only] [BUILD_DIR [extra cmake args...]]   (default build-tsan)
#   --build-only   configure and build, run nothing (CI builds in the background meanwhile)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_only=0
if [ "${1:-}" = "--build-only" ]; then
  build_only=1
  shift
fi
dir=${1:-$root/build-tsan}
shift || true
"$root/scripts/setup.sh"
gen=()
if command -v ninja >/dev/null 2>&1; then gen=(-G Ninja); fi
# -O1 -g1: line tables for the reports; MPI off (Open MPI's own threads are not instrumented)
# GCC through CC/CXX: they choose the compiler of a new build directory only (a compiler given
# with -D to an existing one makes CMake drop its cache, and the -D options with it)
CC=gcc CXX=g++ cmake -S "$root" -B "$dir" "${gen[@]}" -DSONARLOOP_TSAN=ON -DSONARLOOP_MPI=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "$@" \
  >/dev/null
if ! grep -q '^SONARLOOP_TSAN:BOOL=ON$' "$dir/CMakeCache.txt"; then
  echo "tsan.sh: $dir is not configured with SONARLOOP_TSAN=ON; remove it and run again" >&2
  exit 2
fi
cmake --build "$dir" -j "$(nproc)"
if [ "$build_only" = 1 ]; then exit 0; fi
# halt_on_error: a reported race fails the test; second_deadlock_stack for lock-order reports;
# the suppressions: Embree's and TBB's uninstrumented threads (scripts/tsan.supp)
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 \
suppressions=$root/scripts/tsan.supp ${TSAN_OPTIONS:-}"
ctest --test-dir "$dir" --output-on-failure -j "$(nproc)"
echo "tsan.sh: the main job, 10 s of the default scenario at --rate max, recorded"
rm -rf "$dir/tsan-run"
"$dir/tools/sonarloop" run --duration 10 --rate max --quiet --record "$dir/tsan-run"
echo "tsan.sh: no race reported"
