#!/usr/bin/env python3
"""The powder front's speed under several definitions, from a die-filling run's snapshots.

The paper gives one "impact velocity" per case (0.266 m/s for Case 1-3, 0.226 m/s for
Case 2-3) "when the tip of the powder touched the die floor", from a figure of the
particles' velocity distribution, without saying which particles it averages. cgdem's
metric (`mean_impact_velocity_m_s`) is the mass-weighted downward speed of the parcels
that reach the floor in the first 5 ms after the front does. This script prints, for each
run and each snapshot time given (default: every snapshot within 6 ms after the front),
the mean speed |v| and the mean downward speed -v_z of
  die          every parcel inside the die (below the table top, over the mouth)
  first        every parcel in the section the front lands in (the section the cavity
               reaches first: shallow for die type 1, deep for type 2)
  0-2 / 2-4 mm the parcels of that section whose centres lie 0-2 / 2-4 mm above its floor
with the parcel count of each, and the run's own metric. The point is the ratio between
die types: the paper's type-2 front is slower than its type-1 front (0.85 at l = 3) although
it falls 12 mm instead of 7 mm; a definition that is to be the paper's must give that too.

Usage:
    /usr/bin/python3 validation/die_filling/impact_definitions.py RUN [RUN ...] [--times 0.1,0.11]
"""
import argparse
import glob
import os
import tomllib

import h5py
import numpy as np
import pandas as pd


def read_time(path):
    with h5py.File(path, "r") as f:
        return float(f.attrs["time"])


def geometry(run):
    path = os.path.join(run, "config.resolved.toml")
    if not os.path.exists(path):
        raise SystemExit(f"{run}: not a run folder of cgdem run (no config.resolved.toml)")
    with open(path, "rb") as f:
        cfg = tomllib.load(f)
    df = cfg["walls"]["die_filling"]
    x0, length = df["mouth_x0"], df["mouth_length"]
    xs = x0 + df["step_fraction"] * length
    top = df["table_top"]
    shallow, deep = top - df["shallow_depth"], top - df["deep_depth"]
    if df["die_type"] == 1:   # the cavity reaches x0 first: shallow left, deep right
        first = (x0, xs, shallow)
    else:                     # deep left
        first = (x0, xs, deep)
    return df["die_type"], (x0, x0 + length, top), first


def metric(run, name):
    path = os.path.join(run, "metrics.csv")
    if not os.path.exists(path):
        return float("nan")
    m = pd.read_csv(path, comment="#", index_col="name")["value"]
    return float(m[name]) if name in m.index else float("nan")


def stats(v, mask):
    n = int(np.count_nonzero(mask))
    if n == 0:
        return n, float("nan"), float("nan")
    return n, float(np.linalg.norm(v[mask], axis=1).mean()), float(-v[mask, 2].mean())


def averages(run, times=None):
    """One dict per snapshot: the run, its die type, the snapshot time, the run's front time and
    metric, and for each set of parcels (die, first, 0-2mm, 2-4mm) its count, mean speed and mean
    downward speed. `times`: snapshot times to pick the nearest of (default: every snapshot
    within 6 ms after the front)."""
    die_type, (mx0, mx1, top), (fx0, fx1, floor) = geometry(run)
    front = metric(run, "front_time_s")
    ours = metric(run, "mean_impact_velocity_m_s")
    snaps = sorted((read_time(p), p) for p in glob.glob(os.path.join(run, "particles_*.h5")))
    if not snaps:
        raise SystemExit(f"{run}: no particle snapshots (particles_*.h5)")
    if times:
        picked = [min(snaps, key=lambda s: abs(s[0] - t)) for t in times]
    else:
        picked = [s for s in snaps if front - 1e-9 <= s[0] <= front + 6e-3]
    rows = []
    for t, path in picked:
        with h5py.File(path, "r") as f:
            x = f["particles/x"][:]
            v = f["particles/v"][:]
        die = (x[:, 0] > mx0) & (x[:, 0] < mx1) & (x[:, 2] < top)
        sec = (x[:, 0] > fx0) & (x[:, 0] < fx1) & (x[:, 2] < top)
        h = x[:, 2] - floor
        row = {"run": os.path.basename(os.path.normpath(run)), "die_type": die_type,
               "t_s": t, "front_s": front, "first_arrivals_m_s": ours}
        for name, mask in (("die", die), ("first", sec), ("0-2mm", sec & (h < 2e-3)),
                           ("2-4mm", sec & (h >= 2e-3) & (h < 4e-3))):
            n, speed, down = stats(v, mask)
            row[f"{name}_n"] = n
            row[f"{name}_speed_m_s"] = speed
            row[f"{name}_down_m_s"] = down
        rows.append(row)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", help="snapshot times [s], comma-separated (default: the front + 0..6 ms)")
    a = ap.parse_args()
    times = [float(t) for t in a.times.split(",")] if a.times else None
    table = pd.DataFrame([r for run in a.runs for r in averages(run, times)])
    with pd.option_context("display.width", 250, "display.max_columns", 40,
                           "display.float_format", "{:.4g}".format):
        print(table.to_string(index=False))


if __name__ == "__main__":
    main()
