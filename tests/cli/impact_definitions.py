#!/usr/bin/python3
"""validation/die_filling/impact_definitions.py on run folders made by hand, whose averages are known.

    impact_definitions.py WORK

Two folders, die type 1 and die type 2, with the die-filling keys the script reads (mouth
30-40 mm, step at its middle, table top 10 mm, shallow 7 mm, deep 12 mm: floors at 3 and
-2 mm), a metrics.csv with the front time 0.1 s and a metric of 0.3 m/s, and snapshots at
0.099, 0.101 and 0.105 s (0.099 s is before the front; 0.107 s would be after 6 ms). Each
snapshot holds, in the section the front lands on (x 30-35 mm) and elsewhere:
  * 2 parcels 1 mm above that section's floor, falling at 0.3 and 0.5 m/s (v_z < 0),
  * 1 parcel 3 mm above it, moving at (0.3, 0, -0.4) m/s: speed 0.5, downward 0.4,
  * 1 parcel in the other half of the die (x 37 mm, 1 mm below the table), at rest,
  * 1 parcel in the shoe (above the table top), at 1 m/s: never counted.
Checks: the default picks the two snapshots in [front, front + 6 ms]; --times picks the
nearest; the counts and the means of every set (die: 4 parcels, mean speed 1.3/4 m/s,
mean downward 1.2/4 m/s; first: 3; 0-2 mm: 2, 0.4 m/s; 2-4 mm: 1, 0.5 / 0.4 m/s) for both
die types, whose first section has the shallow (type 1) or the deep floor (type 2).
"""
import os
import shutil
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "validation", "die_filling"))
import impact_definitions  # noqa: E402
from checklist import check, finish  # noqa: E402

work = sys.argv[1]


shutil.rmtree(work, ignore_errors=True)
top = 0.010
for die_type, floor in ((1, top - 0.007), (2, top - 0.012)):
    run = os.path.join(work, f"type{die_type}")
    os.makedirs(run)
    with open(os.path.join(run, "config.resolved.toml"), "w") as f:
        f.write("# cgdem test, config written by hand\n[walls.die_filling]\n"
                f"die_type = {die_type}\ntable_top = {top}\nmouth_x0 = 0.030\nmouth_length = 0.010\n"
                "step_fraction = 0.5\nshallow_depth = 0.007\ndeep_depth = 0.012\n")
    with open(os.path.join(run, "metrics.csv"), "w") as f:
        f.write("name,value\n# cgdem test\nfront_time_s,0.1\nmean_impact_velocity_m_s,0.3\n")
    x = np.array([[0.031, 0.001, floor + 0.001], [0.033, 0.001, floor + 0.001], [0.034, 0.001, floor + 0.003],
                  [0.037, 0.001, top - 0.001], [0.032, 0.001, top + 0.002]])
    v = np.array([[0, 0, -0.3], [0, 0, -0.5], [0.3, 0, -0.4], [0, 0, 0], [1.0, 0, 0]])
    for t in (0.099, 0.101, 0.105):
        with h5py.File(os.path.join(run, f"particles_{int(round(t * 1e6)):06d}.h5"), "w") as f:
            f.attrs["time"] = t
            f["particles/x"] = x
            f["particles/v"] = v

    rows = impact_definitions.averages(run)
    check([r["t_s"] for r in rows] == [0.101, 0.105],
          f"type {die_type}: the snapshots within 6 ms after the front: {[r['t_s'] for r in rows]}")
    picked = impact_definitions.averages(run, [0.0995])
    check(len(picked) == 1 and picked[0]["t_s"] == 0.099, f"type {die_type}: --times 0.0995 picks 0.099 s")
    r = rows[0]
    check(r["die_type"] == die_type and r["front_s"] == 0.1 and r["first_arrivals_m_s"] == 0.3,
          f"type {die_type}: die type, front time and the run's metric read")
    expected = {"die": (4, 1.3 / 4, 1.2 / 4), "first": (3, 1.3 / 3, 1.2 / 3), "0-2mm": (2, 0.4, 0.4),
                "2-4mm": (1, 0.5, 0.4)}
    for name, (n, speed, down) in expected.items():
        got = (r[f"{name}_n"], r[f"{name}_speed_m_s"], r[f"{name}_down_m_s"])
        check(got[0] == n and abs(got[1] - speed) < 1e-12 and abs(got[2] - down) < 1e-12,
              f"type {die_type}, {name}: {got[0]} parcels, {got[1]:.6f} / {got[2]:.6f} m/s "
              f"(expected {n}: {speed:.6f} / {down:.6f})")

finish()
