#!/usr/bin/python3
"""Figs. 5 and 10 of the paper: distribution of the particle velocity with which the
powder front reaches the die floor (paper: at 0.100 s for die type 1, 0.116 s for type 2).

Reads, per run: config.resolved.toml and impacts.csv (every parcel's first arrival at the
die floor: time, downward speed, mass). The parcels counted are those arriving within
diagnostics.impact_window (5 ms by default) of the first arrival, the same set whose
mass-weighted mean is metrics.csv's mean_impact_velocity_m_s. The histogram is weighted by
mass (a parcel of ratio l counts as its l^3 particles), so runs of different l compare
directly. Dashed: the arrivals within four windows (20 ms), for context. Solid vertical
line: our mass-weighted mean; dotted: the paper's value for the same case (x-1, x-2, x-3;
none for the simply large x-4). One panel per die type:

  fig5_10_impact_velocity.png
"""
import os

import numpy as np

import figlib as fl
from figlib import plt


def arrivals(run):
    im = run.impacts()
    for col in ("t_s", "speed_down_m_s", "mass_kg"):
        if col not in im:
            raise fl.InputError(f"{run.dir}/impacts.csv: no column '{col}'")
    if im["t_s"].size == 0:
        raise fl.InputError(f"{run.dir}/impacts.csv: no impacts (the powder never reached the die floor)")
    return im


def within(im, window):
    sel = im["t_s"] <= im["t_s"].min() + window
    return im["speed_down_m_s"][sel], im["mass_kg"][sel]


def main():
    p = fl.arg_parser(__doc__.split("\n\n")[0])
    p.add_argument("--bin", type=float, default=0.01, help="histogram bin width [m/s] (default 0.01)")
    p.add_argument("--window", type=float,
                   help="count the arrivals within this time of the first [s] (default: each run's "
                        "diagnostics.impact_window, the window of its metrics.csv)")
    p.add_argument("--context", type=float, default=4.0,
                   help="also draw (dashed) the arrivals within this many windows of the first (default 4; 0: no)")
    a = p.parse_args()
    groups = fl.by_die_type(fl.load_runs(a.runs))
    data = {r.case: arrivals(r) for g in groups.values() for r in g}
    vmax = max(float(im["speed_down_m_s"].max()) for im in data.values())
    vmin = min(0.0, min(float(im["speed_down_m_s"].min()) for im in data.values()))
    edges = np.arange(np.floor(vmin / a.bin) * a.bin, vmax + a.bin, a.bin)

    fig, axes = plt.subplots(1, len(groups), figsize=(4.4 * len(groups), 3.4), squeeze=False)
    for ax, (die_type, runs) in zip(axes[0], groups.items()):
        paper = fl.PAPER[die_type]
        top = 0.0
        for run in runs:
            im = data[run.case]
            t0 = float(im["t_s"].min())
            window = a.window or float(run.diag.get("impact_window", 5e-3))
            speed, mass = within(im, window)
            mean = float(np.sum(mass * speed) / np.sum(mass))
            h, _, _ = ax.hist(speed, bins=edges, weights=mass / mass.sum(), histtype="step", color=run.colour,
                              lw=1.4, label=f"{run.label}: front at {t0:.4f} s,\n  "
                                            f"{speed.size} parcels within {window * 1e3:g} ms")
            top = max(top, float(h.max()))
            if a.context > 0:
                cs, cm = within(im, a.context * window)
                h, _, _ = ax.hist(cs, bins=edges, weights=cm / cm.sum(), histtype="step", color=run.colour,
                                  lw=0.8, ls="--", label=f"  {cs.size} parcels within {a.context * window * 1e3:g} ms")
                top = max(top, float(h.max()))
            ax.axvline(mean, color=run.colour, lw=1.2, label=f"  our mean ({window * 1e3:g} ms) {mean:.3f} m/s")
            ref = paper["impact"].get(run.case_index)
            if ref is not None:
                ax.axvline(ref, color=run.colour, ls=":", lw=1.4,
                           label=f"  paper Case {run.case}: {ref:.3f} m/s (front at {paper['front_time']:.3f} s)")
        ax.set_xlabel("downward speed at the die floor [m/s]", fontsize=8)
        ax.set_ylabel(f"mass fraction per {a.bin:g} m/s bin [-]", fontsize=8)
        ax.set_title(f"Die type {die_type}: first arrivals at the die floor [cf. paper Fig. {5 if die_type == 1 else 10}]",
                     fontsize=8)
        ax.set_xlim(0, 1.1 * max(vmax, *paper["impact"].values()))
        ax.set_ylim(0, 1.6 * top)
        ax.legend(fontsize=6, loc="upper left", frameon=False)
        ax.tick_params(labelsize=7)
    fig.tight_layout()
    fl.save(fig, os.path.join(a.outdir, "fig5_10_impact_velocity.png"))


if __name__ == "__main__":
    fl.main_guard(main)
