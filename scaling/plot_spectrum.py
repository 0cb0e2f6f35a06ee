#!/usr/bin/env python3
"""Plots the output of `cgdem spectrum` (run by the command when matplotlib is available).

    python3 scaling/plot_spectrum.py DIR

reads DIR/psd.csv, DIR/coherence.csv and DIR/peaks.csv and writes DIR/psd.png (one panel
per cell, the runs overlaid, dominant peaks marked) and DIR/coherence.png (one panel per
cell pair, with each run's bias level 1/K dashed). PNGs are written to a temporary name
and renamed, like every cgdem output.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_table(path):
    """Returns (comment line, column names, columns as lists of floats or strings)."""
    with open(path, newline="") as f:
        comment = ""
        rows = []
        for row in csv.reader(f):
            if row and row[0].startswith("#"):
                comment = ",".join(row)
                continue
            rows.append(row)
    header, data = rows[0], rows[1:]
    cols = {h: [r[i] for r in data] for i, h in enumerate(header)}
    return comment, header, cols


def floats(values):
    return [float(v) for v in values]


def segments(comment):
    """label -> K from the comment's 'segments a=K;b=K' part."""
    out = {}
    if "segments " in comment:
        for item in comment.split("segments ", 1)[1].strip().split(";"):
            label, _, k = item.rpartition("=")
            if label:
                out[label] = int(k)
    return out


def save(fig, path):
    tmp = f"{path}.tmp-{os.getpid()}"
    fig.savefig(tmp, format="png", dpi=120)
    os.replace(tmp, path)
    plt.close(fig)


def split_column(name):
    label, _, what = name.rpartition(":")
    return label, what


def plot_psd(folder):
    comment, header, cols = read_table(os.path.join(folder, "psd.csv"))
    f = floats(cols["f_Hz"])
    _, _, peaks = read_table(os.path.join(folder, "peaks.csv"))
    cells = []
    for name in header[1:]:
        cell = split_column(name)[1]
        if cell not in cells:
            cells.append(cell)
    fig, axes = plt.subplots(len(cells), 1, figsize=(7, 2.6 * len(cells)), sharex=True, squeeze=False)
    for ax, cell in zip(axes[:, 0], cells):
        for name in header[1:]:
            label, c = split_column(name)
            if c != cell:
                continue
            psd = floats(cols[name])
            (line,) = ax.semilogy(f[1:], psd[1:], lw=1.2, label=label)
            for i in range(len(peaks["run"])):
                if peaks["run"][i] == label and peaks["cell"][i] == cell and peaks["rank"][i] == "1":
                    ax.plot(float(peaks["f_Hz"][i]), float(peaks["psd_Pa2_per_Hz"][i]), "o", color=line.get_color())
        ax.set_ylabel(f"PSD of p_{cell} (Pa$^2$/Hz)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel("f (Hz)")
    fig.suptitle(comment.split(";")[0].split("spectrum: ", 1)[-1], fontsize=8)
    fig.tight_layout()
    save(fig, os.path.join(folder, "psd.png"))


def plot_coherence(folder):
    comment, header, cols = read_table(os.path.join(folder, "coherence.csv"))
    if len(header) < 2:
        return
    f = floats(cols["f_Hz"])
    k = segments(comment)
    pairs = []
    for name in header[1:]:
        pair = split_column(name)[1]
        if pair not in pairs:
            pairs.append(pair)
    fig, axes = plt.subplots(len(pairs), 1, figsize=(7, 2.3 * len(pairs)), sharex=True, squeeze=False)
    for ax, pair in zip(axes[:, 0], pairs):
        for name in header[1:]:
            label, p = split_column(name)
            if p != pair:
                continue
            (line,) = ax.plot(f[1:], floats(cols[name])[1:], lw=1.2, label=label)
            if label in k:
                ax.axhline(1.0 / k[label], ls="--", lw=0.8, color=line.get_color())
        ax.set_ylim(0, 1.02)
        ax.set_ylabel(f"coherence {pair}")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel("f (Hz)   (dashed: bias 1/K)")
    fig.tight_layout()
    save(fig, os.path.join(folder, "coherence.png"))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_spectrum.py DIR")
    plot_psd(sys.argv[1])
    plot_coherence(sys.argv[1])


if __name__ == "__main__":
    main()
