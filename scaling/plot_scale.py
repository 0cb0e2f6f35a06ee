#!/usr/bin/env python3
"""Plots of a `cgdem scale` report folder (PNG files next to scale.md).

Reads only the CSV files the report wrote (budget_<run>.csv, deviation_<run>.csv,
profile.csv, curves.csv, pod_<field>_spectrum.csv, spectrum/psd.csv and spectrum/peaks.csv);
needs matplotlib, nothing else. Every PNG is written to a temporary name and renamed.
Usage: plot_scale.py REPORT_DIR
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402


def read(path):
    """Columns of a CSV file by name (floats where they parse); '#' comment lines skipped."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head, body = rows[0], rows[1:]
    cols = {h: [] for h in head}
    for r in body:
        for h, v in zip(head, r):
            try:
                cols[h].append(float(v))
            except ValueError:
                cols[h].append(v)
    return cols


def save(fig, path):
    tmp = f"{path}.tmp-{os.getpid()}"
    fig.savefig(tmp, format="png", dpi=110)
    os.replace(tmp, path)
    plt.close(fig)


def runs(d, prefix):
    """(run label, columns) of the per-run files <prefix><run>.csv (budget_summary.csv is not a run)."""
    out = []
    for p in sorted(glob.glob(os.path.join(d, prefix + "*.csv"))):
        label = os.path.basename(p)[len(prefix):-4]
        if label != "summary":
            out.append((label, read(p)))
    return out


def deviation_scale(q):
    """The scale S of the deviation (q_l - q_1) / S of a budget quantity (budgets.hpp)."""
    if q.startswith("v_"):
        return "sqrt(2 S_E)"
    if q in ("e_rot", "e_rot_orig"):
        return "its peak at l=1"
    return "S_E"


def budgets(d):
    groups = [("energies", ["e_trans", "e_rot", "e_rot_orig", "e_pot"]),
              ("dissipation", ["e_damp", "e_fric", "w_walls", "w_air", "closure"]),
              ("momentum", ["v_x", "v_y", "v_z"])]
    series = runs(d, "budget_")
    devs = runs(d, "deviation_")
    if not series:
        return
    for name, qs in groups:
        fig, axes = plt.subplots(2, len(qs), figsize=(3.2 * len(qs), 5.8), squeeze=False)
        for k, q in enumerate(qs):
            for label, c in series:
                axes[0][k].plot(c["t"], c[q], label=label)
            for label, c in devs:
                axes[1][k].plot(c["t"], c[q], label=label)
            axes[0][k].set_title(q + (" (m/s)" if q.startswith("v_") else " (J/kg)"), fontsize=10)
            axes[1][k].set_title(f"({q} - l=1) / {deviation_scale(q)}", fontsize=9)
            axes[1][k].set_xlabel("t (s)")
        axes[0][0].legend(fontsize=7)
        what = "centre-of-mass velocity" if name == "momentum" else "energy per unit solid mass"
        fig.suptitle(f"{what}; bottom row: deviation from l=1 over its scale", fontsize=10)
        fig.tight_layout()
        save(fig, os.path.join(d, "budget_" + name + ".png"))


def profile(d):
    p = os.path.join(d, "profile.csv")
    if not os.path.exists(p):
        return
    c = read(p)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    x = c["x_m"]
    half = 0.5 * (x[1] - x[0]) if len(x) > 1 else 0.5
    edges = [x[0] - half] + [xi + half for xi in x]  # x_m are the centres of equal columns
    for h in c:
        if h.startswith("h_"):
            ax.stairs(c[h], edges, label=h[2:-2])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("pile height (m)")
    ax.set_ylim(bottom=0)
    ax.set_title("final pile: top of the highest parcel per column, averaged over y", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, os.path.join(d, "profile.png"))


def curves(d):
    p = os.path.join(d, "curves.csv")
    if not os.path.exists(p):
        return
    c = read(p)
    names = sorted(set(c["curve"]))
    fig, axes = plt.subplots(len(names), 1, figsize=(6, 2.4 * len(names)), squeeze=False)
    for k, n in enumerate(names):
        for run in sorted(set(c["run"])):
            t = [c["t_s"][i] for i in range(len(c["run"])) if c["run"][i] == run and c["curve"][i] == n]
            y = [c["value"][i] for i in range(len(c["run"])) if c["run"][i] == run and c["curve"][i] == n]
            axes[k][0].plot(t, y, label=run)
        axes[k][0].set_ylabel(n)
    axes[0][0].legend(fontsize=7)
    axes[-1][0].set_xlabel("t (s)")
    fig.tight_layout()
    save(fig, os.path.join(d, "curves.png"))


def pod(d):
    for p in glob.glob(os.path.join(d, "pod_*_spectrum.csv")):
        c = read(p)
        fig, ax = plt.subplots(figsize=(5, 3.5))
        for h in c:
            if h.startswith("fraction_"):
                ax.semilogy(c["mode"], c[h], "o-", label=h[len("fraction_"):])
        ax.set_xlabel("mode k")
        ax.set_ylabel("energy fraction lambda_k / sum lambda")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        field = os.path.basename(p)[len("pod_"):-len("_spectrum.csv")]
        ax.set_title(f"POD of the {field.replace('_', ' ')}", fontsize=10)
        ax.legend(fontsize=7)
        fig.tight_layout()
        save(fig, p[:-4] + ".png")


def pressure_psd(d):
    """Overlay of the runs' Welch PSD of p at each cell (spectrum/psd.csv), peaks marked."""
    p = os.path.join(d, "spectrum", "psd.csv")
    if not os.path.exists(p):
        return
    c = read(p)
    peaks = read(os.path.join(d, "spectrum", "peaks.csv"))
    columns = [h for h in c if h != "f_Hz"]
    cells = []
    for h in columns:
        cell = h.rpartition(":")[2]
        if cell not in cells:
            cells.append(cell)
    fig, axes = plt.subplots(len(cells), 1, figsize=(7, 2.6 * len(cells)), sharex=True, squeeze=False)
    for ax, cell in zip(axes[:, 0], cells):
        for h in columns:
            run, _, col_cell = h.rpartition(":")
            if col_cell != cell:
                continue
            (line,) = ax.semilogy(c["f_Hz"][1:], c[h][1:], lw=1.2, label=run)
            for i in range(len(peaks["run"])):
                if peaks["run"][i] == run and peaks["cell"][i] == cell and peaks["rank"][i] == 1:
                    ax.plot(peaks["f_Hz"][i], peaks["psd_Pa2_per_Hz"][i], "o", color=line.get_color())
        ax.set_ylabel(f"PSD of p_{cell} (Pa$^2$/Hz)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel("f (Hz)   (dots: dominant peak of each run)")
    fig.tight_layout()
    save(fig, os.path.join(d, "pressure_psd.png"))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    budgets(d)
    profile(d)
    curves(d)
    pod(d)
    pressure_psd(d)
    print("plots written to " + d)


if __name__ == "__main__":
    main()
