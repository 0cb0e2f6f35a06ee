#!/usr/bin/python3
"""Checks that every CSV file of a cgdem run folder describes itself (src/io/csv_series.hpp)
and reads with numpy and pandas as is.

    check_csv.py RUN_DIR           every *.csv in RUN_DIR; exit status 1 on any failure
    check_csv.py --self-test DIR   also requires the checks to fail on files of the layout
                                   before units (written into DIR)

For each file: numpy.genfromtxt(names=True, comments="#", delimiter=",") and
pandas.read_csv(comment="#") must both read it, agree on the column names and on the number
of rows, find only numbers (no object dtype, the same NaNs; the text columns of TEXT below
excepted, which must hold text and say so); the column line must be the
first line; a "# cgdem <revision>, ..." line and the pointer to config.resolved.toml must be
there; every column has one "# <name>: <unit>, <description>" line, and its name ends with
the unit's suffix ('/' and ' ' written '_', '^' dropped) or, with unit 1, is one of the
dimensionless columns below. metrics.csv (name,value rows) is checked the same way, its
metric names against the suffix rule instead of its two columns.
"""
import os
import re
import sys
import warnings

import numpy as np
import pandas as pd

# The dimensionless columns (unit 1, no suffix), as documented in src/io/csv_series.hpp and
# README.md: counts and indices.
DIMENSIONLESS = {"particles", "removed", "inside_walls", "impacts", "bubbles", "bin", "parcels", "id",
                 # air_steps.csv: the solvers' counts, a flag and a relative residual
                 "pressure_iterations", "pressure_converged", "pressure_residual", "drag_iterations",
                 "drag_evaluations",
                 # timings.csv: counts of a run
                 "threads", "ranks", "calls", "dem_steps", "fluid_steps", "list_builds"}
# The only columns that hold text (unit 1, described as "text: ..."), per file: timings.csv is
# in long form (one row per phase), so pandas reads it as is, numpy with dtype=None.
TEXT = {"timings.csv": {"revision", "group", "phase"}}
# metrics.csv: the SI suffixes its metric names end with (io/metrics.hpp).
METRIC_SUFFIXES = ("_s", "_kg", "_m", "_Pa", "_J", "_kg_s", "_m_s", "_m3", "_m3_s", "_Hz", "_1_s", "_J_m3")


def suffix(unit):
    return "" if unit == "1" else unit.replace("^", "").replace("/", "_").replace(" ", "_")


def check(path):
    """Failures (strings) of one file; prints what it measured."""
    bad = []
    name = os.path.basename(path)
    with open(path) as f:
        lines = f.read().splitlines()
    body = [l for l in lines if l and not l.startswith("#")]
    if not body:
        return [f"{name}: no column line"]
    if lines[0].startswith("#"):
        bad.append(f"{name}: the first line is not the column line: {lines[0]}")
    columns = body[0].split(",")
    comments = [l[1:].strip() for l in lines if l.startswith("#")]
    if name == "metrics.csv" and not comments:
        # io/metrics.cpp writes name,value rows without '#' lines (yet): the metric names and
        # values are checked below, the provenance and descriptions are not there to check.
        print("metrics.csv: NOTE no provenance or description lines (io/metrics.cpp); names and values checked")
        described = {c: ("", "") for c in columns}
    elif not any(re.match(r"cgdem \S+, ", c) for c in comments):
        bad.append(f"{name}: no '# cgdem <revision>, ...' line")
    if comments and not any("config.resolved.toml" in c for c in comments):
        bad.append(f"{name}: no line naming config.resolved.toml (the resolved configuration)")
    if comments or name != "metrics.csv":
        described = {}
    for c in comments:
        m = re.match(r"([^:\s]+): ([^,]+), (.+)$", c)
        if m and m.group(1) in columns:
            if m.group(1) in described:
                bad.append(f"{name}: column {m.group(1)} described twice")
            described[m.group(1)] = (m.group(2), m.group(3))
    for col in columns:
        if col not in described:
            bad.append(f"{name}: column {col} has no '# {col}: <unit>, <description>' line")
            continue
        unit, _ = described[col]
        if name == "metrics.csv" and not comments:
            continue
        if unit == "1":
            if col in TEXT.get(name, ()):
                if not described[col][1].startswith("text"):
                    bad.append(f"{name}: column {col} holds text but its description does not say so")
            elif col not in DIMENSIONLESS and name != "metrics.csv":
                bad.append(f"{name}: column {col} has unit 1 but is not one of the dimensionless {sorted(DIMENSIONLESS)}")
        elif not col.endswith("_" + suffix(unit)):
            bad.append(f"{name}: column {col} in {unit} does not end with _{suffix(unit)}")
    rows = len(body) - 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy warns, and goes on, on a row it cannot split
        try:
            a = np.atleast_1d(np.genfromtxt(path, names=True, comments="#", delimiter=",",
                                            dtype=None if name == "metrics.csv" or name in TEXT else float,
                                            encoding="utf-8"))
        except Exception as e:  # noqa: BLE001
            return bad + [f"{name}: numpy.genfromtxt failed: {e}"]
    d = pd.read_csv(path, comment="#")
    np_names, pd_names = list(a.dtype.names or []), list(d.columns)
    print(f"{name}: {len(columns)} columns, {rows} rows; numpy {len(np_names)} x {a.shape[0]}, "
          f"pandas {len(pd_names)} x {len(d)}; described {len(described)}")
    if np_names != columns or pd_names != columns:
        bad.append(f"{name}: column names differ: file {columns}, numpy {np_names}, pandas {pd_names}")
    if a.shape[0] != rows or len(d) != rows:
        bad.append(f"{name}: row counts differ: file {rows}, numpy {a.shape[0]}, pandas {len(d)}")
    if rows == 0:
        bad.append(f"{name}: no rows (the test case must produce some)")
    if name == "metrics.csv":
        if pd_names[:2] == ["name", "value"]:
            for n in d["name"]:
                if not (n in DIMENSIONLESS or n.endswith(METRIC_SUFFIXES)):
                    bad.append(f"metrics.csv: metric {n} has no SI suffix and is not dimensionless")
            if d["value"].dtype == object:
                bad.append("metrics.csv: column value is not numeric")
        return bad
    for col in pd_names:
        if col in TEXT.get(name, ()):  # (a revision of decimal digits only would read as a number)
            continue
        if d[col].dtype == object:
            bad.append(f"{name}: column {col} does not parse as numbers (pandas dtype object)")
        elif col in np_names and int(np.isnan(a[col]).sum()) != int(d[col].isna().sum()):
            bad.append(f"{name}: column {col}: numpy and pandas disagree on the NaNs")
    return bad


def old_layout_folder(d):
    """Files as cgdem wrote them before the names carried units."""
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "energy.csv"), "w") as f:
        f.write("# cgdem abc1234, case die.toml\nt,E_kin_trans,mass,particles\n0,1,2,3\n0.1,1,2,3\n")
    with open(os.path.join(d, "diagnostics.csv"), "w") as f:
        f.write("# cgdem abc1234, case die.toml\nt,mass_in_die,p_A\n0,0,nan\n0.1,1,2\n")
    with open(os.path.join(d, "impacts.csv"), "w") as f:
        f.write("id,t,speed_down,mass\n1,0.1,0.2,1e-9\n")


def main():
    args = sys.argv[1:]
    self_test = args[:1] == ["--self-test"]
    if self_test:
        args = args[1:]
    if len(args) != 1:
        sys.exit(__doc__)
    if self_test:
        d = os.path.join(args[0], "old_layout")
        old_layout_folder(d)
        for f in sorted(os.listdir(d)):
            failures = check(os.path.join(d, f))
            print(f"old layout {f}: {len(failures)} failure(s):" + "".join("\n  " + x for x in failures))
            if not failures:
                sys.exit(f"error: the checks pass on the old layout of {f}: they cannot fail")
        return
    files = sorted(f for f in os.listdir(args[0]) if f.endswith(".csv"))
    want = {"energy.csv", "diagnostics.csv", "shoe_surface.csv", "impacts.csv", "metrics.csv"}
    failures = [f"{args[0]}: no {w}" for w in sorted(want - set(files))]
    for f in files:
        failures += check(os.path.join(args[0], f))
    for x in failures:
        print("FAIL", x)
    print(f"{len(files)} CSV files checked, {len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
