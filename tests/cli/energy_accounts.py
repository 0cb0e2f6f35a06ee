#!/usr/bin/python3
"""output.energy_accounts = false, end to end: tests/cli/base.toml with air (1 mm cells),
run with the energy accounts and without them to 8 ms (the lowest parcels on the floor),
a checkpoint every 2 ms.

  * the run without them writes energy.csv with a header line saying so, the columns it did
    not compute described as NOT COMPUTED and nan in every row of them (numpy and pandas);
    the run with them has numbers there, and energy dissipated;
  * every other column (kinetic, potential and elastic energy, the air's work, momentum,
    mass, counts) is the same text in both files: the parcels moved the same to the last
    printed digit;
  * restarting the run without the accounts from its checkpoint with them switched on stops
    with an error that names output.energy_accounts; with the same setting it continues to
    10 ms, the new rows again with nan where nothing was computed;
  * the run with the accounts, restarted without them, stops when it would continue its own
    energy.csv (whose header says computed), leaving the folder's configuration as it was,
    and goes on into another output folder, whose
    energy.csv is new, says NOT COMPUTED and holds nan from the restart on;
  * with --mpiexec, tests/cli/mpi_bed.toml on 2 ranks to 10 ms both ways (pairs split
    between ranks, migration, ghosts): again the same text in every other column.

    energy_accounts.py --cgdem BUILD/cgdem --case tests/cli/base.toml --work DIR
                       [--mpiexec MPIEXEC --mpi_case tests/cli/mpi_bed.toml]
"""
import os
import shutil
import subprocess
import sys

import numpy as np
import pandas as pd

from cli_script import parse_args, verdict

NOT_COMPUTED = ["E_diss_damping_J", "E_diss_friction_J", "W_walls_J", "E_balance_J"]


def main():
    a = parse_args("case", "work", mpiexec="", mpi_case="")
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    failures = []

    def run(out, accounts, *extra):
        cmd = [a.cgdem, "run", a.case, "--output", out, "--set", "air.dx=1e-3", "--set",
               "output.checkpoint_interval=2e-3", "--set", "time.end=8e-3", "--set", f"output.energy_accounts={'true' if accounts else 'false'}",
               *extra]
        return subprocess.run(cmd, capture_output=True, text=True)

    on, off = os.path.join(a.work, "on"), os.path.join(a.work, "off")
    for folder, accounts in ((on, True), (off, False)):
        r = run(folder, accounts)
        if r.returncode != 0:
            return verdict([f"the run with output.energy_accounts = {accounts} failed:\n{r.stdout}\n{r.stderr}"])

    def table(folder):
        path = os.path.join(folder, "energy.csv")
        with open(path) as f:
            lines = f.read().splitlines()
        return lines, pd.read_csv(path, comment="#"), np.genfromtxt(path, names=True, comments="#", delimiter=",")

    lon, don, non = table(on)
    loff, doff, noff = table(off)
    header_off = [l for l in loff if l.startswith("#")]
    if not any("output.energy_accounts = false" in l for l in header_off):
        failures.append("energy.csv without the accounts has no header line saying output.energy_accounts = false")
    for c in NOT_COMPUTED:
        described = [l for l in header_off if l.startswith(f"# {c}: ")]
        if not described or "NOT COMPUTED" not in described[0]:
            failures.append(f"column {c} is not described as NOT COMPUTED: {described}")
        n_pd, n_np = int(doff[c].isna().sum()), int(np.isnan(noff[c]).sum())
        if n_pd != len(doff) or n_np != len(doff):
            failures.append(f"column {c} without the accounts: {n_pd} (pandas) and {n_np} (numpy) nan of {len(doff)} rows")
        if don[c].isna().any():
            failures.append(f"column {c} with the accounts has nan")
    dissipated = don["E_diss_damping_J"].iloc[-1] + don["E_diss_friction_J"].iloc[-1]
    print(f"with the accounts: {len(don)} rows, dissipated {dissipated:.4e} J by t = {don['t_s'].iloc[-1]:g} s, "
          f"balance drift {don['E_balance_J'].iloc[-1] - don['E_balance_J'].iloc[0]:.3e} J; without: "
          f"{len(doff)} rows, nan in {', '.join(NOT_COMPUTED)}")
    if not dissipated > 0:
        failures.append("the run with the accounts dissipated nothing: the comparison would be empty")

    # Every other column, as text.
    def rows(lines):
        body = [l for l in lines if l and not l.startswith("#")]
        names = body[0].split(",")
        keep = [k for k, n in enumerate(names) if n not in NOT_COMPUTED]
        return [names[k] for k in keep], [[r.split(",")[k] for k in keep] for r in body[1:]]

    def compare_other_columns(lines_on, lines_off, what):
        names_on, rows_on = rows(lines_on)
        names_off, rows_off = rows(lines_off)
        differing = sum(x != y for r1, r2 in zip(rows_on, rows_off) for x, y in zip(r1, r2))
        print(f"{what}: the other {len(names_on)} columns, {len(rows_on)} rows: {differing} values differ as text "
              f"(tol 0)")
        if names_on != names_off or len(rows_on) != len(rows_off) or differing:
            failures.append(f"{what}: the runs with and without the accounts differ in {differing} values of the "
                            "other columns")

    compare_other_columns(lon, loff, "one process")

    # Restarts.
    ckpt = os.path.join(off, "checkpoint.bin")
    r = run(off, True, "--restart", ckpt, "--set", "time.end=10e-3")
    print(f"restart without -> with the accounts: exit {r.returncode}; {r.stderr.strip().splitlines()[-1:]}")
    if r.returncode == 0 or "output.energy_accounts" not in r.stderr:
        failures.append("restarting a run without the accounts with them did not stop with an error naming "
                        "output.energy_accounts")
    r = run(off, False, "--restart", ckpt, "--set", "time.end=10e-3")
    if r.returncode != 0:
        failures.append(f"restart with the same setting failed:\n{r.stdout}\n{r.stderr}")
    else:
        _, d2, _ = table(off)
        print(f"restart with the same setting: {len(d2)} rows to t = {d2['t_s'].iloc[-1]:g} s")
        if not (d2["t_s"].iloc[-1] > 2.9e-3 and all(d2[c].isna().all() for c in NOT_COMPUTED)):
            failures.append("the continued run did not reach 10 ms with nan in the columns not computed")
    ckpt_on = os.path.join(on, "checkpoint.bin")
    with open(os.path.join(on, "config.resolved.toml")) as f:
        config_before = f.read()
    r = run(on, False, "--restart", ckpt_on, "--set", "time.end=10e-3")
    with open(os.path.join(on, "config.resolved.toml")) as f:
        if f.read() != config_before:
            failures.append("the refused restart rewrote the folder's config.resolved.toml")
    print(f"restart with -> without the accounts, same folder: exit {r.returncode}; "
          f"{r.stderr.strip().splitlines()[-1:]}")
    if r.returncode == 0 or "another output folder" not in r.stderr:
        failures.append("restarting a run with the accounts without them into its own folder did not stop with an "
                        "error")
    other = os.path.join(a.work, "on_then_off")
    r = run(other, False, "--restart", ckpt_on, "--set", "time.end=10e-3")
    if r.returncode != 0:
        failures.append(f"restart with -> without the accounts into another folder failed:\n{r.stdout}\n{r.stderr}")
    else:
        lines3, d3, _ = table(other)
        print(f"restart with -> without the accounts, another folder: {len(d3)} rows from t = {d3['t_s'].iloc[0]:g} "
              f"to {d3['t_s'].iloc[-1]:g} s")
        says = any(l.startswith("# E_diss_damping_J: ") and "NOT COMPUTED" in l for l in lines3)
        if not (says and all(d3[c].isna().all() for c in NOT_COMPUTED) and d3["t_s"].iloc[-1] > 9.9e-3):
            failures.append("the run restarted without the accounts into another folder does not say NOT COMPUTED "
                            "with nan in every row, or did not reach 10 ms")

    if a.mpiexec:
        folders = []
        for accounts in (True, False):
            folder = os.path.join(a.work, f"mpi_{'on' if accounts else 'off'}")
            r = subprocess.run([a.mpiexec, "--allow-run-as-root", "--oversubscribe", "-np", "2", a.cgdem, "run",
                                a.mpi_case, "--output", folder, "--set", "time.end=10e-3", "--set",
                                f"output.energy_accounts={'true' if accounts else 'false'}"],
                               capture_output=True, text=True)
            if r.returncode != 0:
                failures.append(f"2 ranks, output.energy_accounts = {accounts}: failed\n{r.stdout}\n{r.stderr}")
                return verdict(failures)
            folders.append(folder)
        compare_other_columns(table(folders[0])[0], table(folders[1])[0], "2 MPI ranks")
    return verdict(failures)


if __name__ == "__main__":
    sys.exit(main())
