#!/usr/bin/env bash
# Installs what Aniso_conformal needs from Debian's archive, only if something is missing.
set -euo pipefail
packages=(cmake g++ make libcgal-dev libeigen3-dev libboost-graph-dev libboost-test-dev libpng-dev nlohmann-json3-dev
          libcli11-dev doxygen)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
