#!/usr/bin/env bash
# Configure and build sonarloop (Release). Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
# Builds what the main job needs, the `sonarloop` binary; scripts/test.sh builds everything
# (SONARLOOP_BUILD_ALL=1: every library, tool and test).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
dir=${1:-$root/build}
shift || true
gen=()
if command -v ninja >/dev/null 2>&1; then gen=(-G Ninja); fi
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
else
  cmake -S "$root" -B "$dir" "$@" >/dev/null
fi
target=(--target sonarloop)
if [ "${SONARLOOP_BUILD_ALL:-0}" = 1 ]; then target=(); fi
cmake --build "$dir" -j "$(nproc)" "${target[@]}"
