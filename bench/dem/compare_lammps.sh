#!/usr/bin/env bash
# The dense-bed figures of issues #2 and #20, measured side by side: rounds of LAMMPS on 1
# rank, the engine on 1 and 2 threads, the engine on 1 thread without its energy accounts
# (--no-accounts, as output.energy_accounts = false) and the stripped reference
# (bench/dem/stripped_dem.hpp) without and with the energy accounts,
# interleaved so that a slow spell of the machine hits all of them; prints every value
# and the best and median of each. Needs `apt-get install lammps openmpi-bin`.
# Also LAMMPS on 2 ranks and the engine on 2 threads without the accounts, the peers of a
# two-core run. For a bed in another box than the shared beds' 10 x 6 mm (a bed tiled by
# tile_bed.py), set BOX_X and BOX_Y to the box it printed [m]: the engine gets --box-x/--box-y
# and LAMMPS a copy of its script with the box's walls moved there.
#   usage: [BOX_X=LX BOX_Y=LY] bench/dem/compare_lammps.sh BED.csv [STEPS] [ROUNDS]
set -euo pipefail
bed=$1; steps=${2:-2000}; rounds=${3:-5}
here=$(cd "$(dirname "$0")/../.." && pwd)
cgdem=${CGDEM:-$here/build/cgdem}
lammps=${LAMMPS_RUN:-$here/../shared/bench/dem_bed/lammps/run.sh}
out=$(mktemp); work=$(mktemp -d); trap 'rm -rf "$out" "$work"' EXIT
box=()
if [ -n "${BOX_X:-}${BOX_Y:-}" ]; then
  [ -n "${BOX_X:-}" ] && [ -n "${BOX_Y:-}" ] || { echo "compare_lammps: set both BOX_X and BOX_Y" >&2; exit 2; }
  box=(--box-x "$BOX_X" --box-y "$BOX_Y")
  src=$(dirname "$lammps")
  sed -e "s/^variable Lx .*/variable Lx     equal $BOX_X/" -e "s/^variable Ly .*/variable Ly     equal $BOX_Y/" \
    "$src/in.bench" >"$work/in.bench"
  sed -e "s/0 0.01 xlo xhi/0 $BOX_X xlo xhi/" -e "s/0 0.006 ylo yhi/0 $BOX_Y ylo yhi/" "$lammps" >"$work/run.sh"
  chmod +x "$work/run.sh"
  grep -q "equal $BOX_X\$" "$work/in.bench" && grep -q "equal $BOX_Y\$" "$work/in.bench" &&
    grep -q "0 $BOX_X xlo xhi" "$work/run.sh" && grep -q "0 $BOX_Y ylo yhi" "$work/run.sh" ||
    { echo "compare_lammps: could not move the box's walls in $src (its scripts changed?)" >&2; exit 2; }
  lammps=$work/run.sh
fi
rate() { awk '/particle-steps\/s/{v = $NF == "particle-steps/s" ? $(NF-1) : $NF} END{print v}'; }
bench() { "$cgdem" bench dem --bed "$bed" ${box[@]+"${box[@]}"} --steps "$steps" "$@" | rate; }
for r in $(seq "$rounds"); do
  echo "lammps1 $("$lammps" "$bed" "$steps" 1 | rate)" >>"$out"
  echo "lammps2 $("$lammps" "$bed" "$steps" 2 | rate)" >>"$out"
  echo "cgdem1 $(bench --threads 1)" >>"$out"
  echo "cgdem2 $(bench --threads 2)" >>"$out"
  echo "cgdem1off $(bench --threads 1 --no-accounts)" >>"$out"
  echo "cgdem2off $(bench --threads 2 --no-accounts)" >>"$out"
  echo "stripped $(bench --stripped)" >>"$out"
  echo "accounts $(bench --stripped --accounts)" >>"$out"
  echo "round $r of $rounds done (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
done
echo "bed $(basename "$bed"), $steps steps, $rounds rounds (particle-steps/s)"
table=$(for k in lammps1 lammps2 cgdem1 cgdem2 cgdem1off cgdem2off stripped accounts; do
  awk -v k="$k" '$1==k{print $2}' "$out" | sort -g |
    awk -v k="$k" '{v[NR]=$1; all=all sprintf(" %.3e", $1)} END{printf "%-9s best %.3e median %.3e  all (sorted):%s\n", k, v[NR], v[int((NR+1)/2)], all}'
done)
echo "$table"
echo "$table" | awk '{b[$1]=$3; m[$1]=$5} END{
  printf "cgdem 1 thread / LAMMPS 1 rank: best %.2f, median %.2f (issue #20 target >= 2.0)\n", b["cgdem1"]/b["lammps1"], m["cgdem1"]/m["lammps1"];
  printf "cgdem 1 thread without the accounts / LAMMPS 1 rank: best %.2f, median %.2f (issue #20 target >= 2.5)\n", b["cgdem1off"]/b["lammps1"], m["cgdem1off"]/m["lammps1"];
  printf "cgdem 2 threads / cgdem 1 thread: best %.2f, median %.2f (target >= 1.85)\n", b["cgdem2"]/b["cgdem1"], m["cgdem2"]/m["cgdem1"];
  printf "stripped reference / LAMMPS 1 rank: best %.2f, median %.2f\n", b["stripped"]/b["lammps1"], m["stripped"]/m["lammps1"];
  printf "stripped reference with the energy accounts / LAMMPS 1 rank: best %.2f, median %.2f\n", b["accounts"]/b["lammps1"], m["accounts"]/m["lammps1"];
  printf "cgdem 1 thread / stripped reference with the accounts: best %.2f, median %.2f (target >= 0.9)\n", b["cgdem1"]/b["accounts"], m["cgdem1"]/m["accounts"];
  printf "cgdem 1 thread without the accounts / stripped reference without them: best %.2f, median %.2f\n", b["cgdem1off"]/b["stripped"], m["cgdem1off"]/m["stripped"];
  printf "cgdem 2 threads / LAMMPS 2 ranks: best %.2f, median %.2f; without the accounts: best %.2f, median %.2f\n", b["cgdem2"]/b["lammps2"], m["cgdem2"]/m["lammps2"], b["cgdem2off"]/b["lammps2"], m["cgdem2off"]/m["lammps2"];
  # Issue #20 target 4: Case 1-1 is 540,000 particles x 360,000 steps of a mostly settled bed.
  n = 540000 * 360000;
  printf "hours that Case 1-1'"'"'s 1.944e11 particle-steps would take at this bed'"'"'s median rates (a settled bed of its size stands for it: docs/dem_performance.md section 24): LAMMPS 2 ranks %.2f, cgdem 2 threads %.2f, without the accounts %.2f, stripped reference at a perfect 2-thread scaling %.2f (best rate: %.2f)\n", n/m["lammps2"]/3600, n/m["cgdem2"]/3600, n/m["cgdem2off"]/3600, n/(2*m["stripped"])/3600, n/(2*b["stripped"])/3600}'
