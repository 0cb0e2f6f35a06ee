#!/usr/bin/python3
"""The tracer z_start: every parcel carries its height at output.tracer_time in the later
particle snapshots, straight and across a restart.

    tracer.py CGDEM CASE WORK

Runs CASE (a tiny settling bed) to 3 ms with snapshots every 1 ms and the tracer taken at
1 ms, once straight and once stopped at 2 ms and restarted, then checks (tolerance 0: the
tracer is a copy, not a computation):
  * the snapshot at 0 ms has no z_start (before the tracer time);
  * at 1 ms z_start is the parcels' own height x[:, 2];
  * at 2 and 3 ms it is, parcel by parcel (matched by id), the 1 ms height, while the
    parcels have moved (at least one height differs by more than 1 um: the check can fail);
  * the restarted run's 3 ms snapshot carries the same tracer as the straight run's;
  * the dataset states its units (m) and a description.
"""
import glob
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from checklist import check, finish

cgdem, case, work = sys.argv[1:4]


def run(out, *extra):
    args = [cgdem, "run", case, "--set", "time.end=3e-3", "--set", "output.snapshot_interval=1e-3",
            "--set", "output.tracer_time=1e-3", "--set", "output.checkpoint_interval=1e-3", "--output", out, *extra]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"run failed ({r.returncode}): {' '.join(args)}\n{r.stdout}\n{r.stderr}")


def snapshots(folder):
    out = {}
    for path in sorted(glob.glob(os.path.join(folder, "particles_*.h5"))):
        with h5py.File(path, "r") as f:
            t = float(f.attrs["time"])
            order = np.argsort(f["particles/id"][:])
            z0 = f["fields/z_start"] if "fields/z_start" in f else None
            out[round(t * 1e3)] = dict(
                id=f["particles/id"][:][order], z=f["particles/x"][:, 2][order],
                z_start=None if z0 is None else z0[:][order],
                units=None if z0 is None else z0.attrs.get("units"),
                doc=None if z0 is None else z0.attrs.get("description"))
    return out


shutil.rmtree(work, ignore_errors=True)
straight, split = os.path.join(work, "straight"), os.path.join(work, "split")
run(straight)
run(split, "--set", "time.end=2e-3")
run(split, "--restart", os.path.join(split, "checkpoint.bin"))

s = snapshots(straight)
check(sorted(s) == [0, 1, 2, 3], f"snapshots at 0, 1, 2, 3 ms (found {sorted(s)})")
check(s[0]["z_start"] is None, "no z_start before the tracer time")
check(s[1]["z_start"] is not None and np.array_equal(s[1]["z_start"], s[1]["z"]),
      "at the tracer time z_start is the parcels' height")
for ms in (2, 3):
    same_ids = np.array_equal(s[ms]["id"], s[1]["id"])
    check(same_ids and np.array_equal(s[ms]["z_start"], s[1]["z"]), f"at {ms} ms z_start is the 1 ms height")
    moved = np.max(np.abs(s[ms]["z"] - s[1]["z"])) if same_ids else 0
    check(moved > 1e-6, f"the parcels moved since 1 ms (max |dz| = {moved * 1e6:.1f} um > 1 um)")
units = s[3]["units"].decode() if isinstance(s[3]["units"], bytes) else s[3]["units"]
check(units == "m" and bool(s[3]["doc"]), f"z_start has units 'm' ({units}) and a description")
r = snapshots(split)
check(3 in r and r[3]["z_start"] is not None and np.array_equal(r[3]["z_start"], s[3]["z_start"]),
      "the restarted run carries the same tracer")
finish()
