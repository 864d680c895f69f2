#!/usr/bin/env bash
# Idempotent: installs the Debian 12 packages sonarloop needs to build, test and plot.
# Skips apt entirely when everything is already installed.
set -euo pipefail
pkgs=(build-essential cmake ninja-build pkg-config
      libembree-dev libeigen3-dev libyaml-cpp-dev catch2 libpng-dev libjpeg-dev
      libzstd-dev libgdal-dev
      can-utils python3-can python3-numpy python3-matplotlib python3-yaml iproute2
      openmpi-bin libopenmpi-dev)
# for the tests only (scripts/test.sh sets SONARLOOP_BUILD_ALL=1): headless Chromium drives the
# live web view in a real browser (test_web_browser; it skips without it). Large: ~300 MB.
# Node and npm run the independent MCAP reader (@mcap/core from the npm registry) of
# tests/emulator/mcap_reader_test.js; a machine with its own node (e.g. NodeSource's) keeps it.
if [ "${SONARLOOP_BUILD_ALL:-0}" = 1 ]; then
  pkgs+=(chromium)
  if ! command -v npm >/dev/null 2>&1; then pkgs+=(nodejs npm); fi
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
