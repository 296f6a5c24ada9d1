#!/usr/bin/env bash
# Installs the Debian packages snapjump needs, and only those that are missing.
# Used by `make run` and `make test`; safe to run again (it does nothing when all are present).
# Extra packages for other targets come as arguments (`make fuzz`: clang libclang-rt-14-dev).
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libeigen3-dev          # small fixed-size algebra, contact solver
  libtomlplusplus-dev    # case files
  libcli11-dev           # command line
  libfmt-dev             # formatting
  nlohmann-json3-dev     # JSON output
  libudunits2-dev        # units in case files and flags
  libgmsh-dev            # meshes (gmsh C++ API, .msh files)
  libgtest-dev           # tests
  libbenchmark-dev       # benchmarks (bench/)
  openmpi-bin libopenmpi-dev  # sweeps spread over processes (mpirun)
  gnuplot-nox            # figures (snapjump plot)
  pybind11-dev python3-dev   # the Python module (python/)
  python3-numpy python3-pytest  # its arrays and its tests
  help2man               # the man page (cmake --install)
)
packages+=("$@")

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "snapjump: installing missing Debian packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  sudo_cmd=()
elif command -v sudo >/dev/null 2>&1; then
  sudo_cmd=(sudo)
else
  echo "snapjump: these packages are missing and this user cannot install them: ${missing[*]}" >&2
  echo "snapjump: as root, run: apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
