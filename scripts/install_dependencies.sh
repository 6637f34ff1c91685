#!/usr/bin/env bash
# Installs what Aniso_conformal needs from Debian's archive, only if something is missing.
# libopenblas0-serial: CHOLMOD's supernodal factorisation runs on BLAS; with the reference BLAS it is 3 to 10
# times slower (benchmark/scaling.md); the serial variant keeps BLAS from adding threads of its own.
set -euo pipefail
packages=(cmake g++ make libcgal-dev libeigen3-dev libboost-graph-dev libboost-test-dev libpng-dev nlohmann-json3-dev
          libcli11-dev doxygen libsuitesparse-dev libopenblas0-serial)
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
