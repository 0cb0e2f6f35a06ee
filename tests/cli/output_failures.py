#!/usr/bin/python3
"""Output that cannot be written: the run must stop with a non-zero exit and a message
naming the file, and leave the files written before intact and readable.

1. Unwritable output folder. Tests run as root, for whom permission bits do not bind, so
   the folder is asked for under a regular FILE (`--output FILE/out`: ENOTDIR for anyone)
   and under /proc (which refuses mkdir to root too).
2. File size limit (RLIMIT_FSIZE, what `ulimit -f` sets). cgdem ignores SIGXFSZ, so a
   write past the limit fails with EFBIG and must be reported:
   a. a limit below the size of a particle snapshot: the first snapshot fails (HDF5);
   b. a limit between the size of a snapshot and of a checkpoint, on a restart from a
      complete checkpoint: the restarted run's first checkpoint fails, and the previous
      checkpoint.bin must be intact (byte for byte) and restart to the end.
3. A full file system (ENOSPC): a 400 KiB tmpfs, where this process may mount one (root
   outside a restricted container); otherwise this part says it was skipped.

  output_failures.py --cgdem BUILD/cgdem --case tests/cli/base.toml --work DIR
"""
import glob
import os
import resource
import shutil
import subprocess
import sys

import h5py

import cli_script  # tests/cli/cli_script.py: the options and the verdict


def limited(nbytes):
    def pre():
        resource.setrlimit(resource.RLIMIT_FSIZE, (nbytes, nbytes))
    return pre


def readable_h5(d):
    bad = []
    for p in glob.glob(os.path.join(d, "*.h5")):
        try:
            with h5py.File(p, "r") as f:
                f.visititems(lambda n, o: o[()] if isinstance(o, h5py.Dataset) else None)
        except Exception as e:
            bad.append("%s: %s" % (os.path.basename(p), e))
    return bad


def main():
    args = cli_script.parse_args("case", "work")
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = [args.cgdem, "run", args.case, "--set", "output.checkpoint_interval=1e-3"]
    failures = []

    def expect_failure(name, cmd, must_name, preexec=None):
        r = subprocess.run(cmd, capture_output=True, env=env, preexec_fn=preexec)
        err = r.stderr.decode()
        line = [l for l in err.splitlines() if "cgdem: error" in l]
        print("%s: exit %d: %s" % (name, r.returncode, line[0] if line else err.strip()[-300:]))
        if r.returncode <= 0:
            failures.append("%s: exit %d, expected a clean non-zero exit" % (name, r.returncode))
        if must_name not in err:
            failures.append("%s: the message does not name %s" % (name, must_name))
        if "terminate called" in err or "Aborted" in err:
            failures.append(name + ": crashed")
        return r

    # 1. unwritable output folders
    blocker = os.path.join(args.work, "a_file")
    open(blocker, "w").write("not a folder\n")
    expect_failure("output folder under a regular file", run + ["--output", os.path.join(blocker, "out")],
                   os.path.join(blocker, "out"))
    expect_failure("output folder under /proc", run + ["--output", "/proc/cgdem_test_out"], "/proc/cgdem_test_out")

    # Sizes of a normal run's files
    ok = os.path.join(args.work, "ok")
    r = subprocess.run(run + ["--output", ok], capture_output=True, env=env)
    if r.returncode != 0:
        print(r.stderr.decode())
        return 1
    snap = os.path.getsize(os.path.join(ok, "particles_000000.h5"))
    ckpt = os.path.getsize(os.path.join(ok, "checkpoint.bin"))
    print("a normal run writes particle snapshots of %d bytes and checkpoints of %d bytes" % (snap, ckpt))

    # 2a. limit below a snapshot
    d = os.path.join(args.work, "limit_snapshot")
    expect_failure("file size limit %d bytes (below a snapshot)" % (snap // 2), run + ["--output", d],
                   "particles_000000.h5", limited(snap // 2))
    left = glob.glob(os.path.join(d, "*.tmp-*"))
    if left:
        failures.append("temporaries left after a reported failure: %s" % left)

    # 2b. limit between a snapshot and a checkpoint, on a restart from a complete checkpoint
    if not snap < ckpt:
        failures.append("the sizes do not allow the test: snapshot %d >= checkpoint %d bytes" % (snap, ckpt))
    else:
        d = os.path.join(args.work, "limit_checkpoint")
        r = subprocess.run(run + ["--set", "time.end=1e-3", "--output", d], capture_output=True, env=env)
        before = open(os.path.join(d, "checkpoint.bin"), "rb").read()
        lim = (snap + ckpt) // 2
        expect_failure("file size limit %d bytes (between a snapshot and a checkpoint), restarted" % lim,
                       run + ["--output", d, "--restart", os.path.join(d, "checkpoint.bin")], "checkpoint.bin",
                       limited(lim))
        after = open(os.path.join(d, "checkpoint.bin"), "rb").read()
        print("previous checkpoint.bin (%d bytes) intact: %s; unreadable .h5: %s" % (
            len(before), before == after, readable_h5(d) or "none"))
        if before != after:
            failures.append("checkpoint.bin changed by the failed run")
        failures += ["limit_checkpoint: " + b for b in readable_h5(d)]
        left = glob.glob(os.path.join(d, "*.tmp-*"))
        if left:
            failures.append("temporaries left after a reported failure: %s" % left)
        r = subprocess.run(run + ["--output", d, "--restart", os.path.join(d, "checkpoint.bin")], capture_output=True,
                           env=env)
        print("restart from the surviving checkpoint without the limit: exit %d" % r.returncode)
        if r.returncode != 0:
            failures.append("the restart from the surviving checkpoint failed: " + r.stderr.decode()[-300:])
    # 3. a full file system: a 400 KiB tmpfs (when this process may mount one), snapshots
    #    every 0.1 ms until the space runs out (ENOSPC)
    mnt = os.path.join(args.work, "tiny_fs")
    os.makedirs(mnt)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=400k", "tmpfs", mnt], capture_output=True).returncode != 0:
        print("full file system: skipped (cannot mount a tmpfs here; the file-size limit above covers EFBIG)")
    else:
        try:
            d = os.path.join(mnt, "out")
            r = expect_failure("a 400 KiB file system filling up", run + ["--set", "output.snapshot_interval=1e-4",
                                                                          "--output", d], mnt)
            snaps = sorted(glob.glob(os.path.join(d, "particles_*.h5")))
            bad = readable_h5(d)
            print("  left: %d particle snapshots (last %s), checkpoint.bin %s; unreadable .h5: %s; temporaries: %s" % (
                len(snaps), os.path.basename(snaps[-1]) if snaps else "none",
                "present" if os.path.exists(os.path.join(d, "checkpoint.bin")) else "absent", bad or "none",
                [os.path.basename(t) for t in glob.glob(os.path.join(d, "*.tmp-*"))] or "none"))
            failures += ["full file system: " + b for b in bad]
            if not snaps:
                failures.append("full file system: no complete snapshot left")
            if os.path.exists(os.path.join(d, "checkpoint.bin")):
                copy = os.path.join(args.work, "from_full_fs")
                shutil.copytree(d, copy)
                r = subprocess.run(run + ["--set", "output.snapshot_interval=1e-4", "--output", copy, "--restart",
                                          os.path.join(copy, "checkpoint.bin")], capture_output=True, env=env)
                print("  restart from its checkpoint.bin (copied to a folder with space): exit %d" % r.returncode)
                if r.returncode != 0:
                    failures.append("full file system: the restart failed: " + r.stderr.decode()[-300:])
        finally:
            subprocess.run(["umount", mnt])
    return cli_script.verdict(failures)


if __name__ == "__main__":
    sys.exit(main())
