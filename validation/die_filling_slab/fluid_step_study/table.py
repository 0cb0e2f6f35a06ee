#!/usr/bin/env python3
"""The fluid-step study table from `cgdem compare` output and the runs' logs.

Usage: table.py COMPARE_DIR LOG_DIR [PRESSURE_COMPARE_DIR] > table.md

COMPARE_DIR holds metrics_compare.csv and curves_distance.csv of
`cgdem compare REF RUN...` (REF: the semi-implicit run at 1e-4 s); LOG_DIR holds
<label>.log, the standard output of each `cgdem run` (its final report: fluid steps,
pressure iterations, implicit drag solves, per-phase wall time). PRESSURE_COMPARE_DIR, if
given, is a second `cgdem compare` of the same runs over another time range (`--from`),
whose cell-B distance the table reports instead (for example without the die's sealed,
pre-opening phase).
"""
import csv
import re
import sys
from pathlib import Path


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def log_figures(path):
    text = Path(path).read_text() if Path(path).exists() else ""
    out = {}
    m = re.search(r"fluid steps (\d+), mean pressure iterations per step ([\d.]+)", text)
    if m:
        out["steps"], out["pcg"] = int(m.group(1)), float(m.group(2))
    m = re.search(r"wall ([\d.]+) s = DEM ([\d.]+) \+ coupling ([\d.]+) \+ air ([\d.]+)", text)
    if m:
        out["wall"], out["dem"], out["air"] = float(m.group(1)), float(m.group(2)), float(m.group(4))
    m = re.search(r"implicit drag: \d+ nonlinear solves, ([\d.]+) iterations and ([\d.]+) air steps", text)
    out["air_steps"] = float(m.group(2)) if m else 1.0
    return out


def main():
    cmp_dir, log_dir = Path(sys.argv[1]), Path(sys.argv[2])
    metrics = {r["metric"]: r for r in read_csv(cmp_dir / "metrics_compare.csv")}
    dist = read_csv(cmp_dir / "curves_distance.csv")
    if len(sys.argv) > 3:  # cell B's distance from the second comparison
        dist = [r for r in dist if r["curve"] != "p_B"] + \
            [r for r in read_csv(Path(sys.argv[3]) / "curves_distance.csv") if r["curve"] == "p_B"]
    runs = [k for k in metrics["front_time_s"] if k not in ("metric", "unit") and ":" not in k]
    ref = runs[0]

    def l2(curve, run):
        for r in dist:
            if r["curve"] == curve and r["run"] == run:
                return float(r["normalized_l2"])
        return float("nan")

    def val(metric, run, scale=1.0):
        v = metrics[metric][run]
        return float(v) * scale if v else float("nan")

    print("| run | fluid steps | air steps per fluid step | wall s (air s) | front s | impact m/s | "
          "rate peak g/s (at s) | p_B peak Pa (at s) | L2 mass in die | L2 rate | L2 p_B |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for run in runs:
        lg = log_figures(log_dir / f"{run}.log")
        dists = ("reference" if run == ref else f"{l2('mass_in_die', run):.3f}",
                 "" if run == ref else f"{l2('transfer_rate', run):.3f}",
                 "" if run == ref else f"{l2('p_B', run):.3f}")
        print(f"| {run} | {lg.get('steps', '?')} | {lg['air_steps']:.2f} | {lg.get('wall', float('nan')):.0f} "
              f"({lg.get('air', float('nan')):.0f}) | {val('front_time_s', run):.4f} | "
              f"{val('mean_impact_velocity_m_s', run):.3f} | {val('transfer_rate_peak_kg_s', run, 1e3):.2f} "
              f"({val('transfer_rate_peak_time_s', run):.3f}) | {val('p_B_peak_Pa', run):.1f} "
              f"({val('p_B_peak_time_s', run):.3f}) | {dists[0]} | {dists[1]} | {dists[2]} |")


if __name__ == "__main__":
    main()
