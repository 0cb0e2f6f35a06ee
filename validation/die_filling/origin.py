#!/usr/bin/python3
"""Where the die's powder comes from: the shoe layer each parcel in the die started in.

    origin.py RUN [RUN ...] [--times 0.15,0.30] [--output FILE.md]

RUN is a die-filling output folder whose particle snapshots carry the tracer z_start
(output.tracer_time, default 0 s: the parcels' heights when the shoe starts). The shoe's
bed at the tracer time is cut into three layers of equal height, from the table top to
the bed surface (the 99.5th percentile of z_start): bottom, middle, top. For each run and
snapshot time it reports, for the parcels in the die (centre below the table top, inside
the mouth), the share that started in each layer:
  * all of the die's powder;
  * its top layer: in each of ten columns across the mouth (along the shoe's motion) the
    highest third of the column's parcels (so a stepped floor and a partial fill are
    handled alike);
  * the half of the die the cavity reaches first and the half it reaches last;
  * in the shoe, the bottom 3 mm of the bed within 2 mm of the cavity's front wall and of its
    rear wall (a nose, the bed's front slumping so that its top layer cascades down to the
    table, shows as top-layer parcels at the front wall's foot).
With --profile, the bed's surface height over the cavity in ten bins as well.
The reference (Guo et al., moving-shoe DEM-CFD): in vacuum the die's leading side (read
here as the side the shoe travels towards, the half reached last) fills from the shoe's top
layer (nose flow), the trailing side from its bottom layer (bulk flow); with air a bubble
is held in the die and its top fills mainly from the shoe's bottom layer.
Prints a Markdown table (and writes it to --output when given).
"""
import argparse
import glob
import os
import sys
import tomllib

import h5py
import numpy as np


def snapshot_at(run, t):
    best = None
    for path in glob.glob(os.path.join(run, "particles_*.h5")):
        with h5py.File(path, "r") as f:
            tf = float(f.attrs["time"])
        if best is None or abs(tf - t) < abs(best[0] - t):
            best = (tf, path)
    if best is None:
        sys.exit(f"{run}: no particle snapshots")
    return best


def shares(layer, mask):
    n = int(mask.sum())
    if n == 0:
        return n, [float("nan")] * 3
    return n, [100.0 * np.count_nonzero(layer[mask] == k) / n for k in range(3)]


def analyse(run, t):
    with open(os.path.join(run, "config.resolved.toml"), "rb") as f:
        text = f.read().decode()
    cfg = tomllib.loads(text[text.index("\n") + 1:] if text.startswith("#") else text)
    die = cfg["walls"]["die_filling"]
    top, x0, length = die["table_top"], die["mouth_x0"], die["mouth_length"]
    y0, width = die["mouth_y0"], die["mouth_width"]
    tf, path = snapshot_at(run, t)
    with h5py.File(path, "r") as f:
        if "fields/z_start" not in f:
            sys.exit(f"{path}: no tracer z_start (a snapshot before output.tracer_time, or an older run)")
        x = f["particles/x"][:]
        z0 = f["fields/z_start"][:]
    surface = np.percentile(z0[z0 > top], 99.5)
    h = (surface - top) / 3
    layer = np.clip(np.floor((z0 - top) / h), 0, 2).astype(int)
    in_die = (x[:, 2] < top) & (x[:, 0] > x0) & (x[:, 0] < x0 + length) & (x[:, 1] > y0) & (x[:, 1] < y0 + width)
    col = np.clip(((x[:, 0] - x0) / length * 10).astype(int), 0, 9)
    upper = np.zeros(len(x), bool)
    for c in range(10):
        idx = np.flatnonzero(in_die & (col == c))
        if len(idx):
            order = idx[np.argsort(x[idx, 2])]
            upper[order[len(order) - len(order) // 3:]] = True
    first = in_die & (x[:, 0] < x0 + 0.5 * length)
    rows = {"die": shares(layer, in_die), "die, top layer": shares(layer, upper),
            "half reached first": shares(layer, first), "half reached last": shares(layer, in_die & ~first)}
    # The shoe's bed: a nose (the bed's front slumping, its top layer cascading down to the
    # table) shows as top-layer parcels in the bottom 3 mm next to the cavity's front wall.
    c0 = die["cavity_x0"] + shoe_travel(die, tf)
    c1 = c0 + die["cavity_size"][0]
    in_shoe = (x[:, 2] > top) & (x[:, 0] > c0) & (x[:, 0] < c1)
    low = in_shoe & (x[:, 2] < top + 3e-3)
    rows["shoe, bottom 3 mm at the front wall (2 mm)"] = shares(layer, low & (x[:, 0] > c1 - 2e-3))
    rows["shoe, bottom 3 mm at the rear wall (2 mm)"] = shares(layer, low & (x[:, 0] < c0 + 2e-3))
    profile = []
    for k in range(10):   # the bed's surface over the cavity, rear to front: 99th percentile of z
        a = c0 + k * (c1 - c0) / 10
        sel = in_shoe & (x[:, 0] >= a) & (x[:, 0] < a + (c1 - c0) / 10)
        profile.append(np.percentile(x[sel, 2], 99) - top if sel.sum() > 5 else float("nan"))
    return tf, surface - top, rows, profile


def shoe_travel(die, t):
    """The shoe's displacement at t from where cavity_x0 places it, at t = 0 (cgdem's Motion
    integrates from t = 0): at rest until shoe_start, its speed ramped linearly to
    shoe_speed over shoe_ramp (the motion of src/geometry/die_filling.hpp). A shoe that
    starts before t = 0 has a negative displacement then."""
    v, t0, ramp = die.get("shoe_speed", 0.0), die.get("shoe_start", 0.0), die.get("shoe_ramp", 1e-3)

    def from_rest(t):
        if t <= t0:
            return 0.0
        if t <= t0 + ramp:
            return 0.5 * v * (t - t0) ** 2 / ramp
        return v * (t - t0 - 0.5 * ramp)
    return from_rest(t) - from_rest(0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", default="0.15,0.30", help="snapshot times [s], comma-separated (the nearest is used)")
    ap.add_argument("--output")
    ap.add_argument("--profile", action="store_true", help="also the shoe bed's surface profile over the cavity")
    a = ap.parse_args()
    profiles = []
    lines = ["| run | t [s] | bed height at tracer time [mm] | parcels of | count | from bottom [%] | middle [%] | top [%] |",
             "|---|---|---|---|---|---|---|---|"]
    for run in a.runs:
        for t in (float(s) for s in a.times.split(",")):
            tf, bed, rows, profile = analyse(run, t)
            name = os.path.basename(os.path.normpath(run))
            for what, (n, s) in rows.items():
                lines.append(f"| {name} | {tf:.3f} | {bed * 1e3:.2f} | {what} | {n} | "
                             f"{s[0]:.1f} | {s[1]:.1f} | {s[2]:.1f} |")
            profiles.append(f"| {name} | {tf:.3f} | " + " | ".join(f"{1e3 * h:.1f}" for h in profile) + " |")
    text = "\n".join(lines) + "\n"
    if a.profile:
        text += ("\nThe shoe's bed surface over the cavity [mm above the table], ten bins from the rear wall "
                 "to the front wall:\n\n| run | t [s] | " + " | ".join(str(k + 1) for k in range(10)) + " |\n|"
                 + "---|" * 12 + "\n" + "\n".join(profiles) + "\n")
    print(text, end="")
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
