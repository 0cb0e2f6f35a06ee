#!/usr/bin/env python3
"""Plots of a `cgdem scale` report folder (PNG files next to scale.md).

Reads only the CSV files the report wrote (budget_<run>.csv, deviation_<run>.csv,
profile.csv, curves.csv, pod_<field>_spectrum.csv); needs matplotlib, nothing else.
Usage: plot_scale.py REPORT_DIR
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    cols = {h: [] for h in head}
    for r in body:
        for h, v in zip(head, r):
            try:
                cols[h].append(float(v))
            except ValueError:
                cols[h].append(v)
    return cols


def runs(d, prefix):
    out = []
    for p in sorted(glob.glob(os.path.join(d, prefix + "*.csv"))):
        out.append((os.path.basename(p)[len(prefix):-4], read(p)))
    return out


def budgets(d):
    groups = [("energies", ["e_trans", "e_rot", "e_rot_orig", "e_pot"]),
              ("dissipation", ["e_damp", "e_fric", "w_walls", "w_air", "closure"]),
              ("momentum", ["v_x", "v_y", "v_z"])]
    series = runs(d, "budget_")
    devs = runs(d, "deviation_")
    for name, qs in groups:
        fig, axes = plt.subplots(2, len(qs), figsize=(3.2 * len(qs), 5.5), squeeze=False)
        for k, q in enumerate(qs):
            for label, c in series:
                axes[0][k].plot(c["t"], c[q], label=label)
            for label, c in devs:
                axes[1][k].plot(c["t"], c[q], label=label)
            axes[0][k].set_title(q + (" (m/s)" if q.startswith("v_") else " (J/kg)"))
            axes[1][k].set_title("deviation / scale")
            axes[1][k].set_xlabel("t (s)")
        axes[0][0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "budget_" + name + ".png"), dpi=110)
        plt.close(fig)


def profile(d):
    p = os.path.join(d, "profile.csv")
    if not os.path.exists(p):
        return
    c = read(p)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for h in c:
        if h.startswith("h_"):
            ax.step(c["x_m"], c[h], where="mid", label=h[2:-2])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("pile height (m)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "profile.png"), dpi=110)
    plt.close(fig)


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
    fig.savefig(os.path.join(d, "curves.png"), dpi=110)
    plt.close(fig)


def pod(d):
    for p in glob.glob(os.path.join(d, "pod_*_spectrum.csv")):
        c = read(p)
        fig, ax = plt.subplots(figsize=(5, 3.5))
        for h in c:
            if h.startswith("fraction_"):
                ax.semilogy(c["mode"], c[h], "o-", label=h[len("fraction_"):])
        ax.set_xlabel("mode k")
        ax.set_ylabel("energy fraction")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(p[:-4] + ".png", dpi=110)
        plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    budgets(d)
    profile(d)
    curves(d)
    pod(d)
    print("plots written to " + d)


if __name__ == "__main__":
    main()
