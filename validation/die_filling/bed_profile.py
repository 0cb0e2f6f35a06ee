#!/usr/bin/env python3
"""The shoe's bed across its cavity, from a die-filling run's particle snapshots.

For each snapshot time and each of N equal bins across the cavity (x, in the shoe's frame:
bin 0 at the trailing wall, bin N-1 at the leading wall) it prints
  h_s   the solid height [mm]: solid volume of the parcels above the table top in the bin,
        per unit area of the bin (cavity length / N times the cavity's width in the domain);
        its weight per unit area is rho_p g h_s (14.7 Pa per mm for Table 1's powder)
  top   the bed's surface above the table [mm]: 95th percentile of the parcel centres' z
  v_z   the bin's mean vertical parcel velocity [mm/s] (> 0: the bed rises)
and the die's mean gauge pressure (its pressure cells in diagnostics.csv: A, B, C in the
cases, the floor cell in validation/fill_ratio; none in vacuum) at that time, so that
the bed's weight where it is thinnest can be set against the pressure under it.

The shoe's position comes from the run's config.resolved.toml (walls.die_filling:
cavity_x0 at t = 0, shoe_start, shoe_ramp with a linear ramp of the speed, shoe_speed),
through origin.py's shoe_travel.

Usage:
    /usr/bin/python3 validation/die_filling/bed_profile.py RUN [RUN ...] [--times 0,0.05,0.1] [--bins 10]
"""
import argparse
import os
import sys
import tomllib

import h5py
import numpy as np
import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from origin import shoe_travel, snapshot_at  # noqa: E402

G = 9.81  # m/s^2


def die_pressure(run, t):
    """Mean gauge pressure of the run's pressure cells at the row nearest t, and their names."""
    d = pd.read_csv(os.path.join(run, "diagnostics.csv"), comment="#")
    i = (d.t_s - t).abs().idxmin()
    cells = [c for c in d.columns if c.startswith("p_") and c.endswith("_Pa")]
    names = ", ".join(c[2:-3] for c in cells)
    return (float(d.loc[i, cells].mean()) if cells else float("nan")), names


def profile(run, times, nbins):
    with open(os.path.join(run, "config.resolved.toml"), "rb") as f:
        cfg = tomllib.load(f)
    df = cfg["walls"]["die_filling"]
    sp = cfg["particles"]["species"][0]
    rho = sp["density"]
    length, width = df["cavity_size"][0], df["cavity_size"][1]
    ymin, ymax = cfg["domain"]["min"][1], cfg["domain"]["max"][1]
    # The cavity's width inside the domain (a slab is narrower than the cavity).
    width = min(width, ymax - ymin) if cfg["domain"].get("periodic", "") == "y" else width
    table = df["table_top"]
    rows = []
    for t in times:
        ts, path = snapshot_at(run, t)
        if abs(ts - t) > 2e-3:
            continue
        with h5py.File(path) as f:
            x, v, d = f["particles/x"][:], f["particles/v"][:], f["particles/d"][:]
        x0 = df["cavity_x0"] + shoe_travel(df, ts)
        vol = np.pi / 6 * d ** 3
        up = x[:, 2] > table
        p_die, cells = die_pressure(run, ts)
        for b in range(nbins):
            lo = x0 + b * length / nbins
            m = up & (x[:, 0] >= lo) & (x[:, 0] < lo + length / nbins)
            hs = vol[m].sum() / (length / nbins * width)
            rows.append(dict(run=os.path.basename(os.path.normpath(run)), t_s=round(ts, 4), bin=b,
                             x_mm=(lo + length / nbins / 2) * 1e3, h_s_mm=hs * 1e3,
                             weight_Pa=rho * G * hs,
                             top_mm=(np.percentile(x[m, 2], 95) - table) * 1e3 if m.sum() > 5 else np.nan,
                             v_z_mm_s=float(np.mean(v[m, 2])) * 1e3 if m.any() else np.nan, p_die_Pa=p_die,
                             cells=cells))
    return pd.DataFrame(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", default="0,0.01,0.05,0.08,0.1,0.11,0.12,0.13,0.14")
    ap.add_argument("--bins", type=int, default=10)
    ap.add_argument("--csv", help="also write the table here")
    a = ap.parse_args()
    times = [float(s) for s in a.times.split(",")]
    out = pd.concat([profile(r, times, a.bins) for r in a.runs], ignore_index=True)
    for (run, t), g in out.groupby(["run", "t_s"], sort=False):
        cells = g.cells.iloc[0]
        p = f"die pressure (mean of {cells}) {g.p_die_Pa.iloc[0]:.1f} Pa" if cells else "no pressure cells"
        print(f"{run}  t = {t:.3f} s  {p}; "
              f"thinnest bin {g.h_s_mm.min():.2f} mm of solid = {g.weight_Pa.min():.1f} Pa of weight")
        for col, fmt in (("h_s_mm", "{:5.2f}"), ("top_mm", "{:5.2f}"), ("v_z_mm_s", "{:5.0f}")):
            print(f"  {col:9s} trailing " + " ".join(fmt.format(v) for v in g[col]) + " leading")
    if a.csv:
        out.to_csv(a.csv, index=False, float_format="%.5g")


if __name__ == "__main__":
    main()
