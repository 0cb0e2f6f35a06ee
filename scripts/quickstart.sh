#!/usr/bin/env bash
# README command 1: install what is missing, build, run the default case.
#   scripts/quickstart.sh [extra arguments for `cgdem run`, e.g. --set time.end=0.30]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out=out/die_filling_vacuum_l3
./build/cgdem run cases/die_filling_vacuum_l3.toml --output "$out" "$@"
echo "cgdem: results in $(pwd)/$out (open particles.xdmf in ParaView; energy.csv is the energy budget)"
