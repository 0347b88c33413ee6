#!/usr/bin/env bash
# Installs whichever of rbsf's Debian build dependencies are missing.
# Idempotent; prints nothing when everything is already present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  ompl-demos python3 sqlite3
  coinor-libipopt-dev
  # An optimised BLAS for MUMPS's dense frontal matrices (it becomes libblas.so.3 through
  # Debian's alternatives): about a quarter off each Ipopt iteration against the reference
  # BLAS. The serial build:
  # Ipopt solves run one per thread.
  libopenblas0-serial
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libxml2-utils
  # Headless Chromium renders the HTML report in the picture tests.
  chromium
  clang-14 libclang-rt-14-dev
  # The Python module (python/, docs/python.md), its tests and examples, on Debian's python3.
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib
  python3-yaml
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
