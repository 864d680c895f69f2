#!/usr/bin/env bash
# Installs clang and compiler-rt (the sanitizers' and libFuzzer's runtimes, not pulled in without
# recommends) from Debian when missing: the fuzz harnesses (scripts/fuzz.sh) and CI's sanitizer
# build use them.
set -euo pipefail
missing=()
for p in clang libclang-rt-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -ne 0 ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "installing ${missing[*]}" >&2
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi
