#!/usr/bin/env bash
# Fails when a source file includes a header of a layer it may not depend on.
#   sim      <- sim only (no sockets, files or wall clock: design rule)
#   drivers  <- drivers only
#   config   <- config, sim (it loads YAML into sim's descriptions)
#   emulator <- emulator, sim, drivers
#   atr      <- atr, drivers (the onboard side must not link the simulator)
#   autonomy <- autonomy, atr, drivers (the example agent: what a vehicle would run)
#   tools    <- anything
#   units/ (header-only constants, e.g. angles) may be included from every layer
# KNOWN lists the crossings that exist today and are to be removed (issue "Clean seams"); a new
# crossing fails, and so does a listed one that is gone (so the list only shrinks).
# Usage: scripts/check_layers.sh [SOURCE_ROOT]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

declare -A allowed=(
  [sim]="sim units"
  [drivers]="drivers units"
  [config]="config sim units"
  [emulator]="emulator sim drivers units"
  [atr]="atr drivers units"
  [autonomy]="autonomy atr drivers units"
)

KNOWN=(
  "atr/chip_cutter.h -> sim/render/chip_renderer.h"
  "atr/sweep.h -> sim/render/chip_renderer.h"
  "atr/waterfall.h -> sim/core/geodesy.h"
)

found=()
for layer in "${!allowed[@]}"; do
  while IFS= read -r line; do
    file=${line%%:*}
    [[ $line =~ \#include\ \"([^\"]+)\" ]] || continue
    header=${BASH_REMATCH[1]}
    top=${header%%/*}
    ok=0
    for a in ${allowed[$layer]}; do
      [ "$top" = "$a" ] && ok=1
    done
    [ $ok = 1 ] || found+=("$file -> $header")
  done < <(grep -rHE '^#include "[a-z_]+/' "$layer" --include='*.h' --include='*.cpp' || true)
done

# contains NEEDLE ITEMS...: true if NEEDLE is one of ITEMS
contains() {
  local needle=$1
  shift
  for item in "$@"; do [ "$item" = "$needle" ] && return 0; done
  return 1
}

status=0
for f in "${found[@]}"; do
  if ! contains "$f" "${KNOWN[@]}"; then
    echo "layer violation: $f" >&2
    status=1
  fi
done
for k in "${KNOWN[@]}"; do
  if ! contains "$k" "${found[@]}"; then
    echo "gone (remove it from KNOWN in $0): $k" >&2
    status=1
  fi
done
if [ $status = 0 ]; then
  echo "layers: ${#found[@]} known crossings left, no new ones"
fi
exit $status
