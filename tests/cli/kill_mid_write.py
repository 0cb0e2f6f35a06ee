#!/usr/bin/python3
"""SIGKILL at random moments (fixed seed) of a run that writes snapshots and checkpoints
often; after each kill every output file must be readable and the run must continue
from the checkpoint that survived, to the state of a run that was never killed.

Case: tests/cli/base.toml with air on 1 mm cells, a particle and an air snapshot and a
checkpoint every 0.1 ms (every 100 DEM steps), to 2 ms. Each round starts the run and kills
it with SIGKILL, in turn: after a random delay from the start; after a random delay from
the moment the first checkpoint (t = 0) appeared; or, after such a delay, as soon as a
temporary output file (`*.tmp-<pid>`) exists. Then
  * open every .h5 with h5py (every dataset read in full),
  * parse every .xdmf with xml.etree, and require each .h5 it references to exist,
  * restart from checkpoint.bin (`cgdem run CASE --restart DIR/checkpoint.bin`): it must
    exit 0 and print the state digest of the uninterrupted run, and remove (and name) the
    temporaries the killed run left.
Prints how many kills landed while a file was being written (a temporary existed after
the kill) and fails on any unreadable file, failed restart or differing digest.

  kill_mid_write.py --cgdem BUILD/cgdem --case tests/cli/base.toml --work DIR [--kills 12] [--seed 7]
"""
import glob
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import h5py

import cli_script  # tests/cli/cli_script.py: the options and the verdict


def read_all_h5(path):
    """Opens the file and reads every dataset; returns the number of datasets."""
    n = 0
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            nonlocal n
            if isinstance(obj, h5py.Dataset):
                obj[()]
                n += 1
        f.visititems(visit)
    return n


def check_folder(d):
    """Every .h5 and .xdmf readable; returns (h5 count, xdmf count, problems)."""
    problems, n_h5, n_xdmf = [], 0, 0
    for p in sorted(glob.glob(os.path.join(d, "*.h5"))):
        try:
            read_all_h5(p)
            n_h5 += 1
        except Exception as e:  # any failure to read is a torn file
            problems.append("%s: %s" % (os.path.basename(p), e))
    for p in sorted(glob.glob(os.path.join(d, "*.xdmf"))):
        try:
            root = ET.parse(p).getroot()
            n_xdmf += 1
            for item in root.iter("DataItem"):
                ref = (item.text or "").strip().split(":")[0]
                if ref.endswith(".h5") and not os.path.exists(os.path.join(d, ref)):
                    problems.append("%s references %s, which does not exist" % (os.path.basename(p), ref))
        except ET.ParseError as e:
            problems.append("%s: %s" % (os.path.basename(p), e))
    return n_h5, n_xdmf, problems


def digest(out):
    m = re.search(r"state digest ([0-9a-f]+) at t = ([0-9.e+-]+)", out)
    return (m.group(1), m.group(2)) if m else None


def main():
    args = cli_script.parse_args("case", "work", kills=12, seed=7)
    rng = random.Random(args.seed)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    common = [args.cgdem, "run", args.case, "--set", "air.dx=1e-3", "--set", "output.snapshot_interval=1e-4",
              "--set", "output.checkpoint_interval=1e-4", "--set", "output.energy_interval=1e-4"]

    t0 = time.time()
    ref = subprocess.run(common + ["--output", os.path.join(args.work, "reference")], capture_output=True, env=env)
    t_ref = time.time() - t0
    if ref.returncode != 0 or not digest(ref.stdout.decode()):
        print("reference run failed (exit %d):\n%s" % (ref.returncode, ref.stderr.decode()))
        return 1
    want = digest(ref.stdout.decode())
    print("reference run: %.2f s wall, state digest %s at t = %s s" % (t_ref, want[0], want[1]))

    failures, mid_write, no_checkpoint, removed_after = [], 0, 0, 0
    for k in range(args.kills):
        d = os.path.join(args.work, "kill_%02d" % k)
        mode = ["random delay", "after the first checkpoint", "at a temporary"][k % 3]
        delay = rng.uniform(0.0, 0.8) * t_ref
        p = subprocess.Popen(common + ["--output", d], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
        start = time.time()

        def wait_for(pattern):
            while p.poll() is None and time.time() - start < 5 * t_ref + 5 and not glob.glob(os.path.join(d, pattern)):
                time.sleep(0.0005)

        if mode == "random delay":  # from the start: may land before the first checkpoint
            time.sleep(delay)
        else:  # the delay counts from the first checkpoint (t = 0), so that a restart follows
            wait_for("checkpoint.bin")
            time.sleep(delay * (0.25 if k % 6 == 1 else 1.0))
            if mode == "at a temporary":
                wait_for("*.tmp-%d" % p.pid)
        p.send_signal(signal.SIGKILL)
        p.wait()
        p.stderr.close()
        temps = [os.path.basename(t) for t in glob.glob(os.path.join(d, "*.tmp-%d" % p.pid))]
        if temps:
            mid_write += 1
        n_h5, n_xdmf, problems = check_folder(d)
        ckpt = os.path.join(d, "checkpoint.bin")
        line = "kill %2d (%s, %.3f s): exit %d, temporaries left %s, %d .h5 and %d .xdmf read" % (
            k, mode, time.time() - start, p.returncode,
            temps or "none", n_h5, n_xdmf)
        if problems:
            failures.append("kill %d: unreadable output: %s" % (k, "; ".join(problems)))
        if p.returncode != -signal.SIGKILL:
            line += " (the run ended before the kill)"
        if not os.path.exists(ckpt):
            no_checkpoint += 1  # killed before the first checkpoint: start afresh
            r = subprocess.run(common + ["--output", d], capture_output=True, env=env)
            line += "; no checkpoint yet, rerun"
        else:
            r = subprocess.run(common + ["--output", d, "--restart", ckpt], capture_output=True, env=env)
            m = re.search(r"restarting from .* at t = ([0-9.e+-]+) s", r.stdout.decode())
            line += "; restart from t = %s s" % (m.group(1) if m else "?")
        got = digest(r.stdout.decode())
        line += ": exit %d, digest %s" % (r.returncode, got[0] if got else "none")
        print(line)
        if r.returncode != 0:
            failures.append("kill %d: the restart failed (exit %d): %s" % (k, r.returncode, r.stderr.decode()[-500:]))
        elif got != want:
            failures.append("kill %d: the restart ended in %s, the uninterrupted run in %s" % (k, got, want))
        n_h5, n_xdmf, problems = check_folder(d)
        if problems:
            failures.append("kill %d: after the restart: %s" % (k, "; ".join(problems)))
        stale = glob.glob(os.path.join(d, "*.tmp-*"))
        if stale:
            failures.append("kill %d: temporaries of the killed run still there after the restart: %s" % (k, stale))
        elif temps:
            removed_after += 1
            if "temporary file(s) left in" not in r.stderr.decode():
                failures.append("kill %d: the restart removed the temporaries without saying so" % k)
    print("%d kills: %d landed while a file was being written (a temporary was left; removed by the next run: %d), "
          "%d before the first checkpoint; unreadable files, failed or differing restarts: %d" % (
              args.kills, mid_write, removed_after, no_checkpoint, len(failures)))
    status = cli_script.print_failures(failures)
    if mid_write == 0:
        print("FAIL no kill landed during a write: the test did not test what it says")
        return 1
    return status


if __name__ == "__main__":
    sys.exit(main())
