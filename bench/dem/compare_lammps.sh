#!/usr/bin/env bash
# The dense-bed figures of issues #2 and #20, measured side by side: rounds of LAMMPS on 1
# rank, the engine on 1 and 2 threads, the engine on 1 thread without its energy accounts
# (--no-accounts, as output.energy_accounts = false) and the stripped reference
# (bench/dem/stripped_dem.hpp) without and with the energy accounts,
# interleaved so that a slow spell of the machine hits all of them; prints every value
# and the best and median of each. Needs `apt-get install lammps openmpi-bin`.
#   usage: bench/dem/compare_lammps.sh BED.csv [STEPS] [ROUNDS]
set -euo pipefail
bed=$1; steps=${2:-2000}; rounds=${3:-5}
here=$(cd "$(dirname "$0")/../.." && pwd)
cgdem=${CGDEM:-$here/build/cgdem}
lammps=${LAMMPS_RUN:-$here/../shared/bench/dem_bed/lammps/run.sh}
out=$(mktemp); trap 'rm -f "$out"' EXIT
rate() { awk '/particle-steps\/s/{v = $NF == "particle-steps/s" ? $(NF-1) : $NF} END{print v}'; }
for r in $(seq "$rounds"); do
  echo "lammps1 $("$lammps" "$bed" "$steps" 1 | rate)" >>"$out"
  echo "cgdem1 $("$cgdem" bench dem --bed "$bed" --steps "$steps" --threads 1 | rate)" >>"$out"
  echo "cgdem2 $("$cgdem" bench dem --bed "$bed" --steps "$steps" --threads 2 | rate)" >>"$out"
  echo "cgdem1off $("$cgdem" bench dem --bed "$bed" --steps "$steps" --threads 1 --no-accounts | rate)" >>"$out"
  echo "stripped $("$cgdem" bench dem --bed "$bed" --steps "$steps" --stripped | rate)" >>"$out"
  echo "accounts $("$cgdem" bench dem --bed "$bed" --steps "$steps" --stripped --accounts | rate)" >>"$out"
  echo "round $r of $rounds done (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
done
echo "bed $(basename "$bed"), $steps steps, $rounds rounds (particle-steps/s)"
table=$(for k in lammps1 cgdem1 cgdem2 cgdem1off stripped accounts; do
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
  printf "cgdem 1 thread without the accounts / stripped reference without them: best %.2f, median %.2f\n", b["cgdem1off"]/b["stripped"], m["cgdem1off"]/m["stripped"]}'
