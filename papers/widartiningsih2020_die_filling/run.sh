#!/usr/bin/env bash
# Runs the paper's die-filling cases with cgdem and rebuilds every figure of this folder
# from their raw output (README.md here).
#
#   papers/widartiningsih2020_die_filling/run.sh [options] [CASE ...] [-- extra cgdem run arguments]
#
#   CASE        1_1 1_2 1_3 1_4 2_1 2_2 2_3 2_4, or "all" (default: 1_3 2_3, the l = 3 cases).
#               Wall time on 2 cores, whole runs (t = -0.06 to 0.30 s) at revision 4fa76ae:
#               Case 1-3 826 s, Case 2-4 849 s (19,992 parcels each), Case 1-2 2,054 s
#               (67,472 parcels). Projected, not measured: the original systems 1_1 / 2_1
#               (539,772 parcels) 3.4-4.1 h each (papers/widartiningsih2020_die_filling/README.md).
#   --out DIR   folder for the runs (default: out/widartiningsih2020/<UTC time>_<git revision>
#               under the repository); each case goes to DIR/case_X_Y, its log to
#               DIR/logs/case_X_Y.log, the figures to DIR/figures, the numbers to DIR/table.md
#   --threads N OpenMP threads of each run (default: cgdem's, all cores)
#   --figures-only   run nothing, rebuild figures and table from the case folders in --out
#
# The physics is the case files' in validation/die_filling/ (not copied here). The only
# setting the figures depend on is passed explicitly: particle and air snapshots every
# 0.01 s, which include the paper's figure times (0.10, 0.11, 0.15, 0.18, 0.19 s and the
# final state at 0.30 s). A case whose folder already has metrics.csv is not rerun; one
# with checkpoint.bin but no metrics.csv continues from it (bit for bit, cgdem --restart).
# Environment: CGDEM (default build/cgdem), PYTHON (default /usr/bin/python3, which has
# Debian's python3-numpy, python3-matplotlib, python3-h5py).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
cgdem=${CGDEM:-$repo/build/cgdem}
python=${PYTHON:-/usr/bin/python3}
[ -x "$python" ] || python=python3

cases=()
out=""
threads=""
figures_only=0
failed=0
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --figures-only) figures_only=1; shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    all) cases+=(1_1 1_2 1_3 1_4 2_1 2_2 2_3 2_4); shift ;;
    [12]_[1-4]) cases+=("$1"); shift ;;
    *) echo "run.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ ${#cases[@]} -gt 0 ] || cases=(1_3 2_3)

rev=$(git -C "$repo" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
if [ -z "$out" ]; then
  [ $figures_only = 0 ] || { echo "run.sh: --figures-only needs --out DIR" >&2; exit 2; }
  out=$repo/out/widartiningsih2020/$(date -u +%Y%m%dT%H%M%SZ)_$rev
fi
if [ $figures_only = 1 ]; then
  [ -d "$out" ] || { echo "run.sh: no folder $out" >&2; exit 1; }
else
  mkdir -p "$out/logs"
fi
out=$(cd "$out" && pwd)

if [ $figures_only = 0 ]; then
  [ -x "$cgdem" ] || { echo "run.sh: no cgdem binary at $cgdem (build it: scripts/build.sh)" >&2; exit 1; }
  for c in "${cases[@]}"; do
    case_file=$repo/validation/die_filling/case_$c.toml
    dir=$out/case_$c
    log=$out/logs/case_$c.log
    if [ -f "$dir/metrics.csv" ]; then
      echo "case $c: already finished in $dir, not rerun"
      continue
    fi
    cmd=("$cgdem" run "$case_file" --output "$dir" --set output.snapshot_interval=0.01)
    [ -z "$threads" ] || cmd+=(--threads "$threads")
    [ ! -f "$dir/checkpoint.bin" ] || cmd+=(--restart "$dir/checkpoint.bin")
    [ ${#extra[@]} -eq 0 ] || cmd+=("${extra[@]}")
    echo "case $c -> $dir (log $log)"
    {
      echo "# run.sh: $(date -u +%Y-%m-%dT%H:%M:%SZ) start, repository revision $rev, $(nproc) cores"
      echo "# command: ${cmd[*]}"
    } >> "$log"
    start=$(date +%s)
    if "${cmd[@]}" 2>&1 | tee -a "$log"; then
      echo "# run.sh: $(date -u +%Y-%m-%dT%H:%M:%SZ) end, elapsed $(( $(date +%s) - start )) s" >> "$log"
    else
      echo "# run.sh: $(date -u +%Y-%m-%dT%H:%M:%SZ) FAILED after $(( $(date +%s) - start )) s" >> "$log"
      echo "run.sh: case $c failed, see $log" >&2
      failed=1
    fi
  done
fi

runs=()
for d in "$out"/case_*; do [ -f "$d/config.resolved.toml" ] && runs+=("$d"); done
[ ${#runs[@]} -gt 0 ] || { echo "run.sh: no case folders in $out" >&2; exit 1; }
mkdir -p "$out/figures"
cd "$here"
status=$failed
for script in fig_snapshots.py fig_impact_velocity.py fig_transfer_rate.py fig_pressure.py; do
  "$python" "$script" "${runs[@]}" --outdir "$out/figures" || status=1
done
"$python" table.py "${runs[@]}" > "$out/table.md" && echo "wrote $out/table.md" || status=1
echo "run.sh: runs and figures in $out"
exit $status
