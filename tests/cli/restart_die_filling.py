#!/usr/bin/python3
"""Restart of the die filling with air: Case 1-3's geometry (validation/die_filling/case_1_3.toml)
reduced to 1.2 mm air cells (70 x 35 x 25, the table top on a cell face), ~720 parcels
(solid_volume 20e-9 m^3) inserted in the shoe's cavity at t = 0 moving down at 0.5 m/s (so
that they hit the table and each other: contact history, damping and friction) while the
shoe starts to slide, to T = 8 ms. Run once straight to T; once to T/2 and then from its checkpoint to T.
The final particle and air snapshots (every dataset) must be bitwise equal, and so must
the state digests (DEM state with contact history, air fields with ghost layers and
eps_old), energy.csv and diagnostics.csv.

  restart_die_filling.py --cgdem BUILD/cgdem --case validation/die_filling/case_1_3.toml --work DIR
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

import cli_script  # tests/cli/cli_script.py: the options and the verdict

T = 8e-3


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return out


def last(d, stem):
    files = sorted(glob.glob(os.path.join(d, stem + "_*.h5")))
    return files[-1] if files else None


def main():
    args = cli_script.parse_args("case", "work")
    shutil.rmtree(args.work, ignore_errors=True)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    common = [args.cgdem, "run", args.case, "--set", "air.dx=1.2e-3", "--set", "time.start=0.0",
              "--set", "particles.insert[0].solid_volume=20e-9", "--set", "particles.insert[0].velocity=[0.0, 0.0, -0.5]",
              "--set", "output.snapshot_interval=1e-3",
              "--set", "output.checkpoint_interval=1e-3", "--set", "output.energy_interval=1e-4"]
    straight, split = os.path.join(args.work, "straight"), os.path.join(args.work, "split")
    runs = [("straight to T", common + ["--set", "time.end=%g" % T, "--output", straight]),
            ("to T/2", common + ["--set", "time.end=%g" % (T / 2), "--output", split]),
            ("T/2 to T (restart)", common + ["--set", "time.end=%g" % T, "--output", split, "--restart",
                                            os.path.join(split, "checkpoint.bin")])]
    outs = []
    for name, cmd in runs:
        t0 = time.time()
        r = subprocess.run(cmd, capture_output=True, env=env)
        out = r.stdout.decode()
        m = re.search(r"state digest ([0-9a-f]+) at t = ([0-9.e+-]+)", out)
        head = re.search(r"cgdem \S+: (\d+) particles", out)
        print("run %-20s exit %d, %.1f s wall, %s particles, digest %s" % (
            name, r.returncode, time.time() - t0, head.group(1) if head else "?", m.group(1) if m else "none"))
        if r.returncode != 0 or not m:
            print(r.stderr.decode()[-2000:])
            return 1
        outs.append(m.groups())
    failures = []
    if outs[0] != outs[2]:
        failures.append("state digest %s (straight) vs %s (restarted)" % (outs[0], outs[2]))
    for stem in ("particles", "air"):
        a, b = last(straight, stem), last(split, stem)
        if not a or not b or os.path.basename(a) != os.path.basename(b):
            failures.append("final %s snapshots: %s vs %s" % (stem, a, b))
            continue
        da, db = datasets(a), datasets(b)
        differing = [k for k in da if k not in db or da[k].dtype != db[k].dtype or da[k].shape != db[k].shape
                     or da[k].tobytes() != db[k].tobytes()]
        n_values = sum(v.size for v in da.values())
        print("final %s snapshot %s: %d datasets, %d values, bitwise different: %s" % (
            stem, os.path.basename(a), len(da), n_values, differing or "none"))
        for k in differing:
            if k in db and da[k].shape == db[k].shape and np.issubdtype(da[k].dtype, np.number):
                print("  %s: max |difference| %.3g" % (k, np.max(np.abs(da[k].astype(float) - db[k].astype(float)))))
        if differing:
            failures.append("%s snapshot datasets differ: %s" % (stem, differing))
    for csv in ("energy.csv", "diagnostics.csv"):
        sa = open(os.path.join(straight, csv)).read().split("\n")[1:]  # the first line names the case
        sb = open(os.path.join(split, csv)).read().split("\n")[1:]
        print("%s: %d rows, identical: %s" % (csv, len(sa), sa == sb))
        if sa != sb:
            failures.append(csv + " differs")
    return cli_script.verdict(failures, "PASS: the restarted die filling with air is bit-identical")


if __name__ == "__main__":
    sys.exit(main())
