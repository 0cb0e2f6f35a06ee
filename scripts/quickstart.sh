#!/usr/bin/env bash
# README command 1: install what is missing, build, run the default case (the paper's
# Case 1-3: die type 1, l = 3, with air).
#   scripts/quickstart.sh [extra arguments for `cgdem run`, e.g. --set time.end=0.15]
#   CGDEM_CASE=cases/die_filling_vacuum_l3.toml scripts/quickstart.sh   (any other case)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
case_file=${CGDEM_CASE:-validation/die_filling/case_1_3.toml}
out=out/$(basename "$case_file" .toml)
./build/cgdem run "$case_file" --output "$out" "$@"
echo "cgdem: results in $(pwd)/$out (diagnostics.csv, metrics.csv; open particles.xdmf and air.xdmf in ParaView)"
