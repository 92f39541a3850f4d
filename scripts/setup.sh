#!/usr/bin/env bash
# Installs strictmin's dependencies from Debian's archive and builds it in Release (build/).
# Usage: bash scripts/setup.sh      (as root, or with sudo available)
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkgconf
  libeigen3-dev libsuitesparse-dev libopenblas-dev libtbb-dev
  libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev libpng-dev
  libgmp-dev  # GMP's C++ integers (gmpxx.pc): the integer-grid rounding's Hermite normal form
  python3 python3-numpy python3-cvxopt
  python3-dev pybind11-dev python3-pybind11 python3-pytest python3-meshio python3-matplotlib
  python3-setuptools python3-wheel python3-pip python3-venv
  chromium
  clang libclang-rt-14-dev  # the parsers' fuzz targets (libFuzzer), run by the tests' fuzz_smoke
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
echo "setup: built build/strictmin" >&2
