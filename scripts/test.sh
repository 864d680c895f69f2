#!/usr/bin/env bash
# Build (Release) everything, tests included, and run every test.
# Usage: scripts/test.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$root/build}
shift || true
SONARLOOP_BUILD_ALL=1 "$root/scripts/build.sh" "$dir" "$@"
ctest --test-dir "$dir" --output-on-failure -j "$(nproc)"
