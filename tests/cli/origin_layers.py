#!/usr/bin/python3
"""validation/die_filling/origin.py on a run folder made by hand, whose answer is known.

    origin_layers.py WORK

The folder holds a config.resolved.toml with the die-filling keys origin.py reads and one
particle snapshot at t = 12 ms with the tracer z_start. The shoe (speed 0.1 m/s, ramped over
2 ms from t = 0) has travelled 1.1 mm; the table top is at 10 mm and the bed's tracer heights
are 11.5, 14.5 and 17.5 mm (one per third: bottom, middle, top). Parcels are placed:
  * in the die's half reached first: 6 from the bottom third, 2 from the top, stacked in
    one column (the highest third of that column, 2 of 8 parcels: the 2 from the top);
  * in the die's half reached last: 3 from the middle, in one column (its highest third:
    1 parcel);
  * in the shoe at the foot of the cavity's front wall (moved 1.1 mm): 4 from the top third;
    at the foot of its rear wall: 5 from the bottom; high in the bed (4.0-4.9 mm above the
    table, one bin of the profile): 10 from each third.
Checks (exact counts and shares) that each row of origin.py counts those parcels, that the
shoe's travel follows the ramp (0.5 v t^2 / ramp, then v (t - ramp / 2)), and that the
surface profile is the bed's top over the cavity.
"""
import os
import shutil
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "validation", "die_filling"))
import origin  # noqa: E402
from checklist import check, finish  # noqa: E402

work = sys.argv[1]


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
top, x0, length, cav_x0, cav_len = 0.010, 0.030, 0.010, 0.015, 0.010
with open(os.path.join(work, "config.resolved.toml"), "w") as f:
    f.write("# cgdem test, config written by hand\n[walls.die_filling]\n"
            f"table_top = {top}\nmouth_x0 = {x0}\nmouth_length = {length}\nmouth_y0 = 0.0\nmouth_width = 0.004\n"
            f"cavity_x0 = {cav_x0}\ncavity_size = [{cav_len}, 0.004, 0.01]\n"
            "shoe_speed = 0.1\nshoe_start = 0.0\nshoe_ramp = 0.002\n")
t = 0.012
travel = 0.1 * (t - 0.001)
zb, zm, zt = 0.0115, 0.0145, 0.0175
pos, z0 = [], []


def add(n, x, z_first, z_start, dz=0.0004):
    for k in range(n):
        pos.append((x, 0.002, z_first + k * dz))
        z0.append(z_start)


add(6, 0.032, 0.002, zb)             # die, half reached first: the column's lower parcels
add(2, 0.032, 0.0045, zt)            # ... and its top two
add(3, 0.038, 0.002, zm)             # die, half reached last
c0, c1 = cav_x0 + travel, cav_x0 + travel + cav_len
add(4, c1 - 0.001, 0.0105, zt)       # the front wall's foot
add(5, c0 + 0.001, 0.0105, zb)       # the rear wall's foot
for z_start in (zb, zm, zt):         # the bed's middle (bin 6 of 10), high up: its top at 14.9 mm
    add(10, c0 + 0.0055, 0.0140, z_start, dz=0.0001)
x, z0 = np.array(pos), np.array(z0)
with h5py.File(os.path.join(work, "particles_012000.h5"), "w") as f:
    f.attrs["time"] = t
    f["particles/x"] = x
    f["fields/z_start"] = z0

tf, bed, rows, profile = origin.analyse(work, t)
check(abs(tf - t) < 1e-15, f"the snapshot at {t} s is used (got {tf})")
check(abs(bed - (zt - top)) < 1e-12, f"bed height {bed * 1e3:.3f} mm = 7.5 mm (the top tracer height, 99.5th percentile)")


def expect(row, n, shares):
    got_n, got = rows[row]
    ok = got_n == n and np.allclose(got, shares, atol=1e-9)
    check(ok, f"{row}: {got_n} parcels, {got[0]:.1f} / {got[1]:.1f} / {got[2]:.1f} % (expected {n}: "
              f"{shares[0]:.1f} / {shares[1]:.1f} / {shares[2]:.1f})")


expect("die", 11, [600 / 11, 300 / 11, 200 / 11])
expect("die, top layer", 3, [0, 100 / 3, 200 / 3])
expect("half reached first", 8, [75, 0, 25])
expect("half reached last", 3, [0, 100, 0])
expect("shoe, bottom 3 mm at the front wall (2 mm)", 4, [0, 0, 100])
expect("shoe, bottom 3 mm at the rear wall (2 mm)", 5, [100, 0, 0])

die = dict(shoe_speed=0.1, shoe_start=0.0, shoe_ramp=0.002)
check(abs(origin.shoe_travel(die, 0.001) - 0.5 * 0.1 * 0.001 ** 2 / 0.002) < 1e-15, "travel during the ramp")
check(abs(origin.shoe_travel(die, t) - travel) < 1e-15, f"travel after the ramp: {origin.shoe_travel(die, t) * 1e3:.4f} mm")
check(origin.shoe_travel(die, -0.01) == 0.0, "no travel before the start")
mid = profile[5]   # the bin holding the 30 parcels high in the bed
check(np.isfinite(mid) and abs(mid - 0.0049) < 5e-5, f"surface over the bin of the bed's middle {mid * 1e3:.3f} mm "
      "(the 99th percentile of its heights, 4.9 mm above the table, within 0.05 mm)")
check(sum(np.isfinite(p) for p in profile) == 1, "the other bins have too few parcels for a surface")

finish()
