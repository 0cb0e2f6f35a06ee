#!/usr/bin/env python3
"""Tile a dense-bed CSV (x,y,z,d in metres, box [0,LX] x [0,LY], floor z = 0) NX x NY times
side by side, for the DEM benchmark at sizes the shared beds do not have:

    bench/dem/tile_bed.py BED.csv NX NY OUT.csv [--box LX LY]
    cgdem bench dem --bed OUT.csv --box-x BX --box-y BY    (BX, BY as printed)

A settled bed presses on its walls: a particle next to a wall overlaps it by a little (at most
0.8 um, 0.3 % of d, in the shared 67,500 bed). Copies placed one box length apart would give
the facing particles twice that overlap with no history, and the energy it stores is
released as a splash at every seam. So copies are placed a gap g = twice the largest wall
overlap apart: copy (a, b) is shifted by (a (LX + g), b (LY + g), 0) and facing particles
start at most touching. The box of the tiled bed, printed, is NX (LX + g) - g by
NY (LY + g) - g. The bed is refused when a particle overlaps a wall by more than 1 % of its
diameter."""
import argparse
import sys

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bed")
    ap.add_argument("nx", type=int)
    ap.add_argument("ny", type=int)
    ap.add_argument("out")
    ap.add_argument("--box", type=float, nargs=2, default=(0.010, 0.006), metavar=("LX", "LY"))
    a = ap.parse_args()
    if a.nx < 1 or a.ny < 1:
        sys.exit("tile_bed: NX and NY must be at least 1")
    bed = np.genfromtxt(a.bed, delimiter=",", names=True)
    for col in ("x", "y", "z", "d"):
        if col not in bed.dtype.names:
            sys.exit(f"tile_bed: {a.bed} has no column {col} (needs x,y,z,d)")
    lx, ly = a.box
    x, y, z, d = (np.asarray(bed[c], dtype=float) for c in ("x", "y", "z", "d"))
    r = 0.5 * d
    wall_overlap = max((r - x).max(), (x + r - lx).max(), (r - y).max(), (y + r - ly).max(), 0.0)
    if wall_overlap > 0.01 * d.max():
        sys.exit(f"tile_bed: a particle of {a.bed} overlaps the box {lx} x {ly} m by {wall_overlap:.3g} m; give --box")
    g = 2 * wall_overlap
    parts = [np.column_stack([x + i * (lx + g), y + j * (ly + g), z, d]) for j in range(a.ny) for i in range(a.nx)]
    out = np.vstack(parts)
    np.savetxt(a.out, out, delimiter=",", header="x,y,z,d", comments="", fmt="%.17g")
    bx, by = a.nx * (lx + g) - g, a.ny * (ly + g) - g
    print(f"tile_bed: {len(out)} particles -> {a.out}; largest wall overlap of the bed {wall_overlap * 1e6:.2f} um, "
          f"gap between copies {g * 1e6:.2f} um; box: --box-x {bx:.9g} --box-y {by:.9g}")


if __name__ == "__main__":
    main()
