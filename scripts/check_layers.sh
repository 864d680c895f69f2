#!/usr/bin/env bash
# Fails when a source file includes a header of a layer it may not depend on. The map below is
# the libraries' link dependencies (each folder's CMakeLists.txt), so that a library includes
# only what it links:
#   common   <- common only (vectors, geodesy, randomness, the chip convention; Eigen only)
#   sim      <- sim, common (no sockets, files or wall clock: design rule)
#   drivers  <- drivers only
#   config   <- config, sim, common (it loads YAML into sim's descriptions)
#   emulator <- emulator, sim, drivers, common
#   atr      <- atr, drivers, common (the onboard side must not link the simulator)
#   study    <- study, atr, sim, drivers, common (the offline resolution study and chip folders)
#   autonomy <- autonomy, atr, drivers, common (the example agent: what a vehicle would run)
#   mission  <- mission, autonomy, study, emulator, atr, config, sim, drivers, common (the closed
#               loop in lock-step, survey scoring, training on surveys and the default model from
#               the built-in scenarios: offline, where the simulator meets the onboard side)
#   web      <- web, emulator, atr, drivers, common (the live view: event hub, page, HTTP
#               server, and the device that feeds it from the emulator)
#   ranks    <- ranks, study, atr, sim, drivers, common (chips and the resolution study's run over
#               the ranks of an MPI job)
#   products <- products, sim, drivers, common (what scene and render write: images, truth)
#   bench    <- bench, config, sim, drivers, common (the renderers' accuracy, measured by bench)
#   tools    <- anything (the commands)
#   units/ (header-only constants, e.g. angles) may be included from every layer
# Every test folder tests/LAYER/... is held to its layer's map plus tests/ (the test support and
# helpers) and Catch2; tests/support to units and tests; tests/fuzz to every layer but tools. The
# tests of emulator and mission may also use config: the scenarios they fly are YAML files, loaded
# as a user's are.
# The build enforces the same map (cmake/SonarloopTargets.cmake, include scopes): a target sees
# the headers of the folders it links and no others; this check also catches an include that
# the build allows through a link a layer should not have.
# Third-party headers belong to one layer each: Embree to sim, yaml-cpp and GDAL to config, MPI
# to ranks.
# Usage: scripts/check_layers.sh [SOURCE_ROOT]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

declare -A allowed=(
  [common]="common units"
  [sim]="sim common units"
  [drivers]="drivers units"
  [config]="config sim common units"
  [emulator]="emulator sim drivers common units"
  [atr]="atr drivers common units"
  [study]="study atr sim drivers common units"
  [autonomy]="autonomy atr drivers common units"
  [mission]="mission autonomy study emulator atr config sim drivers common units"
  [web]="web emulator atr drivers common units"
  [ranks]="ranks study atr sim drivers common units"
  [products]="products sim drivers common units"
  [bench]="bench config sim drivers common units"
  [tools]="tools bench products ranks web mission autonomy study emulator atr config sim drivers common units"
  [units]="units"
)

# third-party header (first path component, or the file name) -> the layers that may include it
declare -A third_party=(
  [embree3]="sim"
  [yaml-cpp]="config"
  [mpi.h]="ranks"
  [gdal.h]="config"
  [cpl_error.h]="config"
  [ogr_srs_api.h]="config"
  [catch2]="tests"
)

violations=()
# check FOLDER LAYER: every project and third-party include of FOLDER's sources is allowed to LAYER
check() {
  local folder=$1 layer=$2 extra=${3:-}
  local line file header top a ok
  while IFS= read -r line; do
    file=${line%%:*}
    if [[ $line =~ \#include\ \"([^\"]+)\" ]]; then
      header=${BASH_REMATCH[1]}
      top=${header%%/*}
      ok=0
      for a in ${allowed[$layer]} $extra; do
        [ "$top" = "$a" ] && ok=1
      done
      [ $ok = 1 ] || violations+=("$file -> $header")
    elif [[ $line =~ \#include\ \<([^\>]+)\> ]]; then
      header=${BASH_REMATCH[1]}
      top=${header%%/*}
      [ -n "${third_party[$top]+set}" ] || continue
      ok=0
      for a in $layer $extra; do
        [[ " ${third_party[$top]} " == *" $a "* ]] && ok=1
      done
      [ $ok = 1 ] || violations+=("$file -> <$header>")
    fi
  done < <(grep -rHE '^#include ["<]' "$folder" --include='*.h' --include='*.cpp' || true)
}

for layer in "${!allowed[@]}"; do
  check "$layer" "$layer"
  extra=tests
  case $layer in emulator | mission) extra="tests config" ;; esac
  if [ -d "tests/$layer" ]; then check "tests/$layer" "$layer" "$extra"; fi
done
allowed[tests_support]="units"
check tests/support tests_support tests
allowed[fuzz]="mission autonomy study emulator atr config sim drivers common units"
check tests/fuzz fuzz tests
# Embree stays inside the simulator's sources: a header that includes it (embree_device.h,
# ray_fan.h) is included only by .cpp files of sim/ and tests/sim/, so no header of sim passes it
# on to the layers above (they hold Embree handles through sim/scene/embree_handles.h)
while IFS= read -r h; do
  while IFS= read -r line; do
    file=${line%%:*}
    case $file in sim/*.cpp | tests/sim/*.cpp) ;; *) violations+=("$file -> $h (an Embree header)") ;; esac
  done < <(grep -rHF "#include \"$h\"" --include='*.h' --include='*.cpp' --exclude-dir='build*' . |
    sed 's|^\./||' || true)
done < <(grep -rlE '^#include <embree3/' sim --include='*.h' || true)
# every source folder (one that holds C++ sources) is checked: a new one must be added to the map
for d in */; do
  d=${d%/}
  case $d in build* | docs | scripts | cmake | tests) continue ;; esac
  [ -n "$(find "$d" \( -name '*.h' -o -name '*.cpp' \) -print -quit)" ] || continue
  [ -n "${allowed[$d]+set}" ] || violations+=("$d/: a folder the layer map does not know")
done

for v in "${violations[@]}"; do
  echo "layer violation: $v" >&2
done
if [ ${#violations[@]} -gt 0 ]; then
  exit 1
fi
echo "layers: no crossings (every source and test folder checked)"
