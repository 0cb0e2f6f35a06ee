#!/usr/bin/python3
"""bench/dem/tile_bed.py and `cgdem bench dem --box-x --box-y` end to end.

A lattice bed of 120 spheres of 1 mm in the shared beds' 10 x 6 mm box, its outer layers
overlapping the walls by 1 um (as a settled bed does), is tiled 3 x 2. Checked:
  * 720 particles, the printed box is 3 (LX + g) - g by 2 (LY + g) - g with g = 2 um;
  * no two particles of different copies overlap (the gap keeps the seams free);
  * `cgdem bench dem` runs the tiled bed in that box, engine and stripped reference, and
    reports 720 particles and no list rebuild;
  * with --rebuild-every 4 it builds the lists 6 times in 20 steps (the first build and 5
    forced ones) and ends in the same state to round-off; --stripped refuses the option;
  * the same bed without --box-x/--box-y stops with one clear line naming the options;
  * tile_bed refuses a bed that overlaps its walls by more than 1 % of a diameter.

  bench_tiled_bed.py CGDEM REPO WORK
"""
import os
import re
import subprocess
import sys

import numpy as np

from cli_script import verdict


def lattice(path, first):
    """10 x 6 x 2 spheres of 1 mm, 1.0002 mm apart, the first layer's centres at `first` m."""
    d, step = 1e-3, 1.0002e-3
    pts = [(first + i * step, first + j * step, 0.5e-3 + k * 1.0e-3 + 1e-9, d)
           for k in range(2) for j in range(6) for i in range(10)]
    np.savetxt(path, np.array(pts), delimiter=",", header="x,y,z,d", comments="", fmt="%.17g")


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def main():
    cgdem, repo, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    tile = [sys.executable, os.path.join(repo, "bench/dem/tile_bed.py")]
    fails = []
    bed, tiled = os.path.join(work, "bed.csv"), os.path.join(work, "tiled.csv")
    lattice(bed, 0.499e-3)  # 1 um into the walls at 0; 0.8 um into those at 10 and 6 mm
    code, out = run(tile + [bed, "3", "2", tiled])
    print(out.strip())
    m = re.search(r"--box-x (\S+) --box-y (\S+)", out)
    if code != 0 or not m:
        return verdict([f"tile_bed failed ({code}): {out}"])
    bx, by = float(m.group(1)), float(m.group(2))
    g = 2e-6
    ex, ey = 3 * (0.010 + g) - g, 2 * (0.006 + g) - g
    print(f"box {bx:.9g} x {by:.9g} m, expected {ex:.9g} x {ey:.9g}")
    if abs(bx - ex) > 1e-12 or abs(by - ey) > 1e-12:
        fails.append(f"box {bx} x {by}, expected {ex} x {ey}")
    t = np.genfromtxt(tiled, delimiter=",", names=True)
    xyz = np.column_stack([t["x"], t["y"], t["z"]])
    if len(xyz) != 720:
        fails.append(f"{len(xyz)} particles, expected 720")
    copy = np.repeat(np.arange(6), 120)
    dist = np.sqrt(((xyz[:, None, :] - xyz[None, :, :]) ** 2).sum(-1))
    across = dist[copy[:, None] != copy[None, :]]
    print(f"closest particles of different copies: {across.min() * 1e6:.4f} um apart (d = 1000 um)")
    if across.min() < 1e-3 * (1 - 1e-12):
        fails.append(f"copies overlap: {across.min()} m < d")
    box = ["--box-x", repr(bx), "--box-y", repr(by)]
    for extra in ([], ["--stripped"]):
        code, out = run([cgdem, "bench", "dem", "--bed", tiled, "--steps", "20"] + box + extra)
        rate = re.search(r"particle-steps/s: (\S+)", out)
        print(f"bench dem {' '.join(extra)}: exit {code}, rate {rate.group(1) if rate else None}")
        if code != 0 or not rate or "720 particles" not in out:
            fails.append(f"bench dem {extra} on the tiled bed: exit {code}: {out}")
        if not extra and "list builds 1," not in out:
            fails.append(f"the engine rebuilt its lists on the tiled bed: {out}")
    # --rebuild-every 4: 5 forced builds in 20 steps (plus the first), and the same motion:
    # the particles are sorted again but the contacts and their sums are the same.
    states = []
    for extra in ([], ["--rebuild-every", "4"]):
        code, out = run([cgdem, "bench", "dem", "--bed", tiled, "--steps", "20"] + box + extra)
        builds = re.search(r"list builds (\d+),", out)
        state = re.search(r"state: E_kin (\S+) E_pot (\S+)", out)
        print(f"bench dem {' '.join(extra)}: exit {code}, list builds {builds.group(1) if builds else None}, "
              f"state {state.groups() if state else None}")
        if code != 0 or not builds or not state:
            fails.append(f"bench dem {extra}: exit {code}: {out}")
            continue
        states.append(tuple(float(v) for v in state.groups()))
        want = 6 if extra else 1
        if int(builds.group(1)) != want:
            fails.append(f"bench dem {extra}: {builds.group(1)} list builds, expected {want}")
    if len(states) == 2 and any(abs(a - b) > 1e-9 * abs(b) for a, b in zip(*states)):
        fails.append(f"forced rebuilds changed the state beyond round-off: {states}")
    code, out = run([cgdem, "bench", "dem", "--bed", tiled, "--steps", "20", "--stripped", "--rebuild-every", "4"] + box)
    print(f"--stripped with --rebuild-every: exit {code}: {out.strip()}")
    if code == 0 or "--rebuild-every" not in out:
        fails.append(f"--stripped with --rebuild-every was not refused clearly: exit {code}: {out}")
    code, out = run([cgdem, "bench", "dem", "--bed", tiled, "--steps", "20"])
    print(f"without --box-x/--box-y: exit {code}: {out.strip()}")
    if code == 0 or "outside the box" not in out or "--box-x" not in out:
        fails.append(f"a tiled bed outside the default box was not refused clearly: exit {code}: {out}")
    lattice(bed, 0.48e-3)  # 20 um into the walls: 2 % of d
    code, out = run(tile + [bed, "2", "1", tiled])
    print(f"bed 20 um into its walls: exit {code}: {out.strip()}")
    if code == 0 or "overlaps the box" not in out:
        fails.append(f"tile_bed accepted a bed 20 um into its walls: {out}")
    return verdict(fails, "all checks passed")


if __name__ == "__main__":
    sys.exit(main())
