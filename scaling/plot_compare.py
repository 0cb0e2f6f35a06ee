#!/usr/bin/env python3
"""Plots of a `cgdem compare` report folder (PNG files next to compare.md).

    python3 scaling/plot_compare.py DIR

Reads DIR/runs_compare.csv (label and folder of each run), DIR/curves_distance.csv (the
compared columns and their units) and DIR/curves_compare.csv (the common time range), then
each run's own diagnostics.csv at full resolution (its columns by quantity: t_s as t,
p_A_Pa as p_A, as in curves_distance.csv), and writes
  DIR/curves.png        mass in the die, transfer rate and every p_ cell pressure, the runs
                        overlaid, one panel each;
  DIR/curves_extra.png  every other compared column (mass_in_shoe, air fluxes, bubbles ...),
                        when there is one.
The x axis is the common time range. Needs matplotlib, nothing else. Every PNG is written
to a temporary name and renamed, like every cgdem output.
"""
import csv
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows_of(path):
    """(comment lines, data rows) of a CSV file; the first data row is the header."""
    comments, rows = [], []
    with open(path, newline="") as f:
        for row in csv.reader(f):
            if row and row[0].startswith("#"):
                comments.append(",".join(row))
            elif row:
                rows.append(row)
    return comments, rows


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def quantity(name, comments):
    """The column's quantity, as `cgdem compare` names its curves: the name without its unit
    suffix (p_A_Pa -> p_A), the unit read from the "# <name>: <unit>, <description>" line;
    the name itself in files written before the names carried units."""
    for c in comments:
        m = re.match(r"#\s*" + re.escape(name) + r": ([^,]+), ", c)
        if m:
            unit = m.group(1)
            sfx = "" if unit == "1" else "_" + unit.replace("^", "").replace("/", "_").replace(" ", "_")
            return name[: -len(sfx)] if sfx and name.endswith(sfx) and len(name) > len(sfx) else name
    return name


def diagnostics(folder):
    """Columns of FOLDER/diagnostics.csv by quantity (t, mass_in_die, p_A ...); restarted rows
    superseded (t increasing)."""
    comments, rows = rows_of(os.path.join(folder, "diagnostics.csv"))
    head, body = [quantity(h, comments) for h in rows[0]], [r for r in rows[1:] if len(r) == len(rows[0])]
    kept = []
    it = head.index("t")
    for r in body:
        t = number(r[it])
        while kept and number(kept[-1][it]) >= t:
            kept.pop()
        kept.append(r)
    return {h: [number(r[i]) for r in kept] for i, h in enumerate(head)}


def main_curve(column):
    return column in ("mass_in_die", "transfer_rate") or column.startswith("p_")


def save(fig, path):
    tmp = f"{path}.tmp-{os.getpid()}"
    fig.savefig(tmp, format="png", dpi=110)
    os.replace(tmp, path)
    plt.close(fig)


def panels(runs, curves, t_range, ncols, path):
    nrows = (len(curves) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(6.5 * ncols, 2.4 * nrows + 0.6), sharex=True, squeeze=False)
    for ax, (column, unit) in zip(axes.flat, curves):
        for label, cols in runs:
            if column in cols:
                ax.plot(cols["t"], cols[column], lw=1.1, label=label)
        ax.set_ylabel(f"{column} ({unit})" if unit else column, fontsize=8)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        if t_range:
            ax.set_xlim(*t_range)
    for ax in list(axes.flat)[len(curves):]:
        ax.set_visible(False)
    for j in range(ncols):  # the lowest panel in use of each column carries the time axis
        rows_used = [i for i in range(nrows) if i * ncols + j < len(curves)]
        if rows_used:
            ax = axes[rows_used[-1], j]
            ax.tick_params(labelbottom=True)
            ax.set_xlabel("t (s)")
    fig.tight_layout()
    save(fig, path)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_compare.py DIR")
    d = sys.argv[1]
    _, run_rows = rows_of(os.path.join(d, "runs_compare.csv"))
    head = run_rows[0]
    runs = [(r[head.index("label")], diagnostics(r[head.index("folder")])) for r in run_rows[1:]]
    _, dist = rows_of(os.path.join(d, "curves_distance.csv"))
    curves = []
    for r in dist[1:]:
        if (r[0], r[1]) not in curves:
            curves.append((r[0], r[1]))
    comments, _ = rows_of(os.path.join(d, "curves_compare.csv"))
    t_range = None
    for c in comments:
        m = re.search(r"common range (\S+) to (\S+) s", c)
        if m:
            t_range = (float(m.group(1)), float(m.group(2)))
    main_curves = [c for c in curves if main_curve(c[0])]
    extra = [c for c in curves if not main_curve(c[0])]
    if main_curves:
        panels(runs, main_curves, t_range, 1, os.path.join(d, "curves.png"))
    if extra:
        panels(runs, extra, t_range, 2, os.path.join(d, "curves_extra.png"))


if __name__ == "__main__":
    main()
