#!/usr/bin/env bash
# Installs the Debian 12 packages cgdem needs, only those that are missing (idempotent).
set -euo pipefail
pkgs=(build-essential cmake git pkg-config
      libsundials-dev libsuitesparse-dev libeigen3-dev libhdf5-dev libfftw3-dev
      libgtest-dev libtoml11-dev libcli11-dev libfmt-dev
      libopenblas0-pthread    # OpenBLAS: reference BLAS makes CHOLMOD ~12x slower
      openmpi-bin libopenmpi-dev  # MPI (src/parallel/mpi, multi-rank tests); optional for the build
      libhypre-dev                # hypre PFMG, the "pfmg" preconditioner of solvers/pressure_mpi; optional
      python3-matplotlib python3-numpy python3-h5py  # plots of the analysis commands (optional at run time)
      python3-pandas   # tests/cli/csv_outputs: every run CSV must read with pandas.read_csv as is
      python3-meshio)  # tests/cli/h5_outputs: particles.xdmf must read with meshio
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "cgdem: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
