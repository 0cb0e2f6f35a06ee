#!/usr/bin/env bash
# README command 2: install what is missing, build, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
# Two tests at a time on the 2 cores; each test single-threaded unless it sets threads itself.
cd build && OMP_NUM_THREADS=1 ctest -j2 --output-on-failure --timeout 900
