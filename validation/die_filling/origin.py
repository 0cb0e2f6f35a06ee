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
  * the half of the die the cavity reaches first and the half it reaches last.
The reference (Guo et al., moving-shoe DEM-CFD): in vacuum the die's leading side fills
from the shoe's top layer (nose flow); with air a bubble is held in the die and its top
fills mainly from the shoe's bottom layer.
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
    return tf, surface - top, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", default="0.15,0.30", help="snapshot times [s], comma-separated (the nearest is used)")
    ap.add_argument("--output")
    a = ap.parse_args()
    lines = ["| run | t [s] | bed height at tracer time [mm] | parcels of | count | from bottom [%] | middle [%] | top [%] |",
             "|---|---|---|---|---|---|---|---|"]
    for run in a.runs:
        for t in (float(s) for s in a.times.split(",")):
            tf, bed, rows = analyse(run, t)
            for what, (n, s) in rows.items():
                lines.append(f"| {os.path.basename(os.path.normpath(run))} | {tf:.3f} | {bed * 1e3:.2f} | {what} | {n} | "
                             f"{s[0]:.1f} | {s[1]:.1f} | {s[2]:.1f} |")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
