#!/usr/bin/env bash
# Installs the Debian 12 packages phasor needs, idempotently: packages already present are not
# touched and apt is not called at all when nothing is missing. Runs apt as root, or through
# sudo; says clearly what to do when neither is possible.
set -euo pipefail

PACKAGES=(
  cmake ninja-build pkgconf g++ make
  libembree-dev libtbb-dev libopenimageio-dev libimath-dev libopencolorio-dev libosd-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev libcerf-dev
  libfmt-dev          # string formatting in the program (src/app)
  libcli11-dev        # the command line and its usage text (src/app/cli.cpp)
  libgtest-dev libbenchmark-dev
  openimageio-tools   # iinfo: the Ctrl-C test reads the partial image's metadata with it
  fonts-dejavu-core   # DejaVu Sans: labels on images drawn by OpenImageIO (core/image/sheet.cpp)
  python3-matplotlib  # every plot (python/phasor_plot.py: profile, compare, probe); brings numpy
  python3-jinja2      # compare's page: results.json through python/templates/compare.html.j2
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests (docs/python.md)
  chromium            # headless: the test that opens `phasor compare`'s page (tests/app/compare.sh)
  libopenmpi-dev openmpi-bin  # MPI (docs/distributed.md): mpirun -n N phasor render …; the MPI tests
)
# Optional extras for `make fuzz` (clang + libFuzzer runtime).
if [[ "${PHASOR_WITH_FUZZ:-0}" == 1 ]]; then
  PACKAGES+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "phasor: installing missing Debian packages: ${missing[*]}" >&2
if [[ $(id -u) -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO=(sudo -n)
else
  echo "phasor: these packages are missing and I cannot install them (not root, no password-less sudo):" >&2
  echo "    sudo apt-get install --no-install-recommends ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
