#!/usr/bin/env python3
"""Plots the output of `cgdem spectrum` (run by the command when matplotlib is available).

    python3 scaling/plot_spectrum.py DIR

reads DIR/psd.csv, DIR/background.csv, DIR/coherence.csv and DIR/peaks.csv and writes
DIR/psd.png (one panel per cell on log-log axes, the runs overlaid, each with its AR(1)
red-noise background dashed, the significance level dotted and the band between them
shaded, the significant peaks marked, the lowest peak frequency as a vertical line) and
DIR/coherence.png (one panel per cell pair, log frequency axis, with each run's bias
level 1/K dashed). PNGs are written to a temporary name
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


def lowest_peak_frequency(comment):
    """The 'peaks from bin 2 (X Hz)' part of the comment, in Hz (None when absent)."""
    if "peaks from bin " not in comment:
        return None
    part = comment.split("peaks from bin ", 1)[1]
    try:
        return float(part.split("(", 1)[1].split(" Hz", 1)[0])
    except (IndexError, ValueError):
        return None


def confidence(comment):
    """The level of the red-noise test from the comment ('above the 0.95 level'), or None."""
    if "above the " not in comment:
        return None
    try:
        return float(comment.split("above the ", 1)[1].split(" ", 1)[0])
    except ValueError:
        return None


def plot_psd(folder):
    comment, header, cols = read_table(os.path.join(folder, "psd.csv"))
    f = floats(cols["f_Hz"])
    _, _, peaks = read_table(os.path.join(folder, "peaks.csv"))
    bg_path = os.path.join(folder, "background.csv")
    bg = read_table(bg_path)[2] if os.path.exists(bg_path) else {}
    f_low = lowest_peak_frequency(comment)
    level = confidence(comment)
    level_text = f"{100 * level:g} % level" if level else "level"
    cells = []
    for name in header[1:]:
        cell = split_column(name)[1]
        if cell not in cells:
            cells.append(cell)
    fig, axes = plt.subplots(len(cells), 1, figsize=(7, 2.8 * len(cells)), sharex=True, squeeze=False)
    for ax, cell in zip(axes[:, 0], cells):
        notes = 0
        for name in header[1:]:
            label, c = split_column(name)
            if c != cell:
                continue
            psd = floats(cols[name])
            # Log frequency axis: the DC bin (f = 0) cannot be drawn and is not a peak anyway.
            (line,) = ax.loglog(f[1:], psd[1:], lw=1.2, label=label)
            colour = line.get_color()
            if f"{name}:background" in bg:
                b = floats(bg[f"{name}:background"])
                lv = floats(bg[f"{name}:level"])
                ax.fill_between(f[1:], b[1:], lv[1:], color=colour, alpha=0.15, lw=0)
                ax.loglog(f[1:], b[1:], ls="--", lw=0.8, color=colour, label=f"{label}: AR(1) background")
                ax.loglog(f[1:], lv[1:], ls=":", lw=1.0, color=colour, label=f"{label}: {level_text}")
            marked = False
            for i in range(len(peaks["run"])):
                if peaks["run"][i] == label and peaks["cell"][i] == cell:
                    ax.plot(float(peaks["f_Hz"][i]), float(peaks["psd_Pa2_per_Hz"][i]), "o", ms=5, color=colour,
                            label=None if marked else f"{label}: significant peak")
                    marked = True
            if not marked:
                ax.text(0.02, 0.05 + 0.08 * notes, f"{label}: no significant peak", transform=ax.transAxes,
                        ha="left", va="bottom", fontsize=7, color=colour)
                notes += 1
        if f_low:
            ax.axvline(f_low, color="0.5", lw=0.8, ls="-.")
        ax.set_ylabel(f"PSD of p_{cell} (Pa$^2$/Hz)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    xlabel = "f (Hz)"
    if f_low:
        xlabel += f"   (dash-dot: lowest peak frequency {f_low:g} Hz; shaded: AR(1) background to its {level_text})"
    axes[-1, 0].set_xlabel(xlabel, fontsize=8)
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
            (line,) = ax.semilogx(f[1:], floats(cols[name])[1:], lw=1.2, label=label)
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
