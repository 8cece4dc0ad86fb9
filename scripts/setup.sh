#!/usr/bin/env bash
# Installs fretwear's build and test dependencies from Debian (12, bookworm), only those that are missing.
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libboost-dev libfmt-dev nlohmann-json3-dev
          doctest-dev libfftw3-dev libcli11-dev libbenchmark-dev gnuplot-nox python3 python3-jsonschema
          chromium pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pandas
          libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: every dependency is installed"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
