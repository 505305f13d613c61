#!/usr/bin/env bash
# Installs the Debian packages the build, the tests and the pictures need. Idempotent: packages that are
# already installed are skipped, so a second run costs a few seconds. Needs root (apt-get).
set -euo pipefail

packages=(
  cmake g++ gfortran make
  trilinos-all-dev libptscotch-dev libscotch-dev   # Trilinos 13.2; its CMake config links (PT-)Scotch
  libmumps-dev                                      # distributed sparse direct solver (LU and LDL^T)
  libhdf5-openmpi-dev openmpi-bin libopenmpi-dev    # parallel HDF5 and MPI
  libgtest-dev                                      # GoogleTest
  libopenblas0-pthread                              # fast BLAS under MUMPS (4x over reference BLAS)
  python3 python3-numpy python3-matplotlib python3-h5py   # plots and output checks
  paraview xvfb                                     # headless rendering of the XDMF output
  snakemake                                         # the studies' workflow (scripts/workflow/Snakefile)
  slurm-wlm munge                                   # a local batch system for the workflow's Slurm test
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-dependencies: missing packages: ${missing[*]}" >&2
  echo "install-dependencies: run this script as root (it calls apt-get)" >&2
  exit 1
fi

echo "install-dependencies: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq "${missing[@]}"
