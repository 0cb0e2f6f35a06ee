#!/usr/bin/python3
"""air_steps.csv: one row per fluid step of a run with air, the figures the final report
sums up ("fluid steps ...", "implicit drag: ..."), straight and across a restart.

    air_steps.py CGDEM CASE WORK

Runs CASE (tests/cli/moving_wall.toml: a paddle sweeps 300 parcels through air) to 3 ms
with plain CG pressure solves (iteration counts that vary from step to step) and air.cfl
0.01 (fluid steps shortened by the CFL limit as the paddle speeds up: steps of varying
length), once with the semi-implicit and once with the implicit drag coupling, and checks:
  * the file describes itself: the column line first, the '# cgdem ...' line, one
    '# name: unit, description' line per column with the expected units, and
    pandas.read_csv(f, comment='#') reads numbers only;
  * one row per fluid step (the summary's "fluid steps N"), times strictly increasing and
    equal to time.start + the cumulative sum of dt_fluid_s (1e-12 relative), the last one
    the run's final time;
  * the mean of pressure_iterations, the unconverged solves and the largest divergences are
    the summary's, to its printed precision;
  * semi-implicit: drag_iterations and drag_evaluations 0, the drag residuals nan;
    implicit: a nonlinear solve every step, the mean drag_iterations and drag_evaluations,
    the largest drag_iterations and drag_residual_m_s the summary's "implicit drag: ..."
    figures, every accepted residual within air.implicit.tolerance;
  * restart: stopped at 1.5 ms and continued from that checkpoint, the file's text equals
    the straight run's; continued a second time from the same checkpoint (the file then
    holds rows after it, which must be dropped), still equal;
  * a run in vacuum writes no air_steps.csv and does not list it.
"""
import os
import re
import shutil
import subprocess
import sys
import tomllib

import numpy as np
import pandas as pd

from checklist import check, finish

cgdem, case, work = sys.argv[1:4]
T, T_HALF, DRAG_TOL = 3e-3, 1.5e-3, 1e-7
UNITS = {"t_s": "s", "dt_fluid_s": "s", "pressure_iterations": "1", "pressure_converged": "1",
         "pressure_residual": "1", "max_divergence_1_s": "1/s", "max_divergence_walls_1_s": "1/s",
         "drag_iterations": "1", "drag_evaluations": "1", "drag_residual_m_s": "m/s",
         "drag_first_residual_m_s": "m/s"}
COUPLING = {"semi-implicit": [], "implicit": ["--set", "air.coupling=implicit",
                                               "--set", f"air.implicit.tolerance={DRAG_TOL}"]}


def run(out, *extra):
    args = [cgdem, "run", case, "--set", f"time.end={T}", "--set", "air.pressure.method=cg",
            "--set", "air.cfl=0.01", "--output", out, *extra]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"run failed ({r.returncode}): {' '.join(args)}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def agrees(value, printed):
    """value equals the printed number to its printed precision (half a unit of its last digit)."""
    mantissa = printed.lower().split("e")[0]
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    scale = 10.0 ** int(printed.lower().split("e")[1]) if "e" in printed.lower() else 1.0
    return abs(value - float(printed)) <= 0.5 * 10.0 ** -decimals * scale * (1 + 1e-9)


def summary(stdout):
    m = re.search(r"fluid steps (\d+), mean pressure iterations per step (\S+), unconverged solves (\d+), max "
                  r"divergence (\S+) 1/s in cells with air \((\S+) 1/s inside walls", stdout)
    d = re.search(r"implicit drag: (\d+) nonlinear solves, (\S+) iterations and (\S+) air steps per fluid step "
                  r"\(at most (\d+)\), largest accepted residual (\S+) m/s", stdout)
    t = re.search(r"state digest [0-9a-f]+ at t = (\S+)", stdout)
    if not m or not t:
        sys.exit(f"no fluid summary or final time in the output:\n{stdout}")
    return m.groups(), d.groups() if d else None, t.group(1)


def rows_of(path):
    """The file's text below its column line and '#' lines (the rows)."""
    with open(path) as f:
        return [l for l in f.read().splitlines()[1:] if not l.startswith("#")]


def check_layout(path, label):
    with open(path) as f:
        lines = f.read().splitlines()
    check(lines[0] == ",".join(UNITS), f"{label}: the column line comes first and is {','.join(UNITS)}")
    check(any(re.match(r"# cgdem \S+, case ", l) for l in lines), f"{label}: a '# cgdem <revision>, case ...' line")
    for name, unit in UNITS.items():
        described = [l for l in lines if l.startswith(f"# {name}: ")]
        m = re.match(rf"# {name}: ([^,]+), (.+)$", described[0]) if len(described) == 1 else None
        check(m is not None and m.group(1) == unit and m.group(2).strip() != "",
              f"{label}: {name} has one '# {name}: {unit}, <description>' line (found {described})")
    d = pd.read_csv(path, comment="#")
    check(list(d.columns) == list(UNITS), f"{label}: pandas reads the columns {list(d.columns)}")
    check(all(d[c].dtype != object for c in d.columns), f"{label}: pandas reads numbers only "
          f"(dtypes {sorted(set(str(d[c].dtype) for c in d.columns))})")
    return d


def check_run(folder, stdout, coupling):
    label = f"{coupling}"
    path = os.path.join(folder, "air_steps.csv")
    check(os.path.exists(path), f"{label}: {path} written")
    check("air_steps.csv" in next((l for l in stdout.splitlines() if l.startswith("outputs in")), ""),
          f"{label}: the outputs line lists air_steps.csv")
    d = check_layout(path, label)
    (n, p_mean, unconverged, div, div_walls), drag, t_final = summary(stdout)
    n = int(n)
    check(len(d) == n, f"{label}: {len(d)} rows, one per fluid step (summary: fluid steps {n})")
    t, dt = d["t_s"].to_numpy(), d["dt_fluid_s"].to_numpy()
    check(len(t) > 1 and bool(np.all(np.diff(t) > 0)), f"{label}: times strictly increasing")
    check(len(np.unique(dt)) > 5, f"{label}: steps of {len(np.unique(dt))} different lengths (the CFL limit acts)")
    with open(os.path.join(folder, "config.resolved.toml"), "rb") as f:
        t0 = float(tomllib.load(f)["time"]["start"])
    err = np.max(np.abs(t - (t0 + np.cumsum(dt)))) / np.max(np.abs(t))
    check(err <= 1e-12, f"{label}: t_s = time.start + cumulative sum of dt_fluid_s (rel. err {err:.1e} <= 1e-12)")
    check(abs(t[-1] - float(t_final)) <= 1e-8 * abs(t[-1]), f"{label}: the last row is at the final time {t_final} s")
    it = d["pressure_iterations"].to_numpy()
    mean = it.sum() / len(it)
    check(np.ptp(it) > 0 and agrees(mean, p_mean),
          f"{label}: mean pressure_iterations {mean:.4f} = summary's {p_mean} (per step {it.min()} .. {it.max()})")
    conv = d["pressure_converged"].to_numpy()
    check(set(np.unique(conv)) <= {0, 1} and int((conv == 0).sum()) == int(unconverged),
          f"{label}: pressure_converged 1/0, {int((conv == 0).sum())} unconverged = summary's {unconverged}")
    res = d["pressure_residual"].to_numpy()
    check(bool(np.all(np.isfinite(res) & (res >= 0))), f"{label}: pressure_residual finite (max {res.max():.2e})")
    for col, printed in (("max_divergence_1_s", div), ("max_divergence_walls_1_s", div_walls)):
        v = d[col].max()
        check(v > 0 and agrees(v, printed), f"{label}: max {col} {v:.4e} = summary's {printed}")
    di, de = d["drag_iterations"].to_numpy(), d["drag_evaluations"].to_numpy()
    r, r0 = d["drag_residual_m_s"].to_numpy(), d["drag_first_residual_m_s"].to_numpy()
    if coupling == "semi-implicit":
        check(drag is None, f"{label}: no 'implicit drag:' summary line")
        check(bool(np.all(di == 0) and np.all(de == 0)), f"{label}: drag_iterations and drag_evaluations all 0")
        check(bool(np.all(np.isnan(r)) and np.all(np.isnan(r0))), f"{label}: drag residuals all nan")
        return
    if drag is None:
        check(False, f"{label}: an 'implicit drag:' summary line")
        return
    solves, i_mean, e_mean, i_max, r_max = drag
    check(bool(np.all(de > 0)) and len(d) == int(solves),
          f"{label}: a nonlinear solve every step ({int((de > 0).sum())} of {len(d)}; summary: {solves} solves)")
    check(agrees(di.sum() / len(di), i_mean),
          f"{label}: mean drag_iterations {di.sum() / len(di):.4f} = summary's {i_mean} (per step {di.min()} .. {di.max()})")
    check(np.ptp(de) > 0 and agrees(de.sum() / len(de), e_mean),
          f"{label}: mean drag_evaluations {de.sum() / len(de):.4f} = summary's {e_mean}")
    check(int(di.max()) == int(i_max), f"{label}: max drag_iterations {di.max()} = summary's {i_max}")
    check(agrees(r.max(), r_max), f"{label}: max drag_residual_m_s {r.max():.4e} = summary's {r_max}")
    check(bool(np.all(r <= DRAG_TOL) and np.all(np.isfinite(r0) & (r0 > 0))),
          f"{label}: every accepted residual <= {DRAG_TOL:g} m/s, first residuals finite (max {r0.max():.2e} m/s)")


shutil.rmtree(work, ignore_errors=True)
for coupling, extra in COUPLING.items():
    straight = os.path.join(work, coupling, "straight")
    split = os.path.join(work, coupling, "split")
    out = run(straight, *extra)
    check_run(straight, out, coupling)
    # Stopped at T/2 (its checkpoint is its last state), continued from a copy of that
    # checkpoint, then continued once more from it over the finished file.
    run(split, *extra, "--set", f"time.end={T_HALF}")
    half = os.path.join(split, "half.bin")
    shutil.copyfile(os.path.join(split, "checkpoint.bin"), half)
    n_half = len(rows_of(os.path.join(split, "air_steps.csv")))
    full = rows_of(os.path.join(straight, "air_steps.csv"))
    check(0 < n_half < len(full) and rows_of(os.path.join(split, "air_steps.csv")) == full[:n_half],
          f"{coupling}: the run stopped at {T_HALF:g} s has the straight run's first {n_half} rows")
    for attempt in ("continued", "continued again over the finished file"):
        out = run(split, *extra, "--restart", half)
        rows = rows_of(os.path.join(split, "air_steps.csv"))
        n = int(re.search(r"fluid steps (\d+)", out).group(1))
        check(rows == full and len(rows) == n,
              f"{coupling}: {attempt} from {T_HALF:g} s: {len(rows)} rows, text equal to the straight run's "
              f"{len(full)} (summary of the restarted run: fluid steps {n})")
    with open(os.path.join(split, "air_steps.csv")) as a, open(os.path.join(straight, "air_steps.csv")) as b:
        check(a.read() == b.read(), f"{coupling}: the continued file equals the straight run's, preamble included")

vacuum = os.path.join(work, "vacuum")
out = run(vacuum, "--set", "air.enabled=false")
check(not os.path.exists(os.path.join(vacuum, "air_steps.csv")) and "air_steps.csv" not in out,
      "a run in vacuum writes no air_steps.csv and does not list it")
finish()
