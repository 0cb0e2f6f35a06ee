#!/usr/bin/python3
"""Figs. 6 and 11 of the paper: mass transfer rate of powder from the shoe into the die.

Reads, per run: config.resolved.toml and diagnostics.csv (column transfer_rate_kg_s: backward
difference of the mass in the die over diagnostics.rate_window, 5 ms by default, one row
every 0.1 ms). Only t >= 0 (the shoe moving) is drawn. A dot marks each run's largest rate;
the dashed line the time of the paper's maximum (about 0.19 s for die type 1, 0.18 s for
type 2). The paper prints no rate values in its text, only the curves. One panel per die
type:

  fig6_11_transfer_rate.png
"""
import os

import numpy as np

import figlib as fl
from figlib import plt


def main():
    a = fl.arg_parser(__doc__.split("\n\n")[0]).parse_args()
    groups = fl.by_die_type(fl.load_runs(a.runs))
    fig, axes = plt.subplots(1, len(groups), figsize=(4.2 * len(groups), 3.2), squeeze=False, sharey=True)
    for ax, (die_type, runs) in zip(axes[0], groups.items()):
        for run in runs:
            d = run.diagnostics()
            t, rate = d["t_s"], d["transfer_rate_kg_s"] * 1e3  # g/s
            keep = t >= 0
            t, rate = t[keep], rate[keep]
            if t.size == 0:
                raise fl.InputError(f"{run.dir}/diagnostics.csv: no rows at t >= 0 yet")
            window = float(run.diag.get("rate_window", 5e-3))
            i = int(np.argmax(rate))
            ax.plot(t, rate, color=run.colour, lw=1.0,
                    label=f"{run.label}" + ("" if t[-1] >= 0.299 else f" (to {t[-1]:.3f} s)"))
            ax.plot(t[i], rate[i], "o", color=run.colour, ms=4,
                    label=f"  our maximum {rate[i]:.1f} g/s at {t[i]:.3f} s")
        tp = fl.PAPER[die_type]["peak_time"]
        ax.axvline(tp, color="k", ls="--", lw=0.8, label=f"paper: maximum at ~{tp:.2f} s")
        ax.set_xlim(0, 0.30)
        ax.set_xlabel("time t [s] (shoe starts at 0)", fontsize=8)
        ax.set_ylabel(f"mass transfer rate [g/s] ({window * 1e3:g} ms window)", fontsize=8)
        ax.set_title(f"Die type {die_type}: shoe -> die [cf. paper Fig. {6 if die_type == 1 else 11}]", fontsize=8)
        ax.set_ylim(top=1.35 * ax.get_ylim()[1])
        ax.legend(fontsize=6, loc="upper right", frameon=False)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fl.save(fig, os.path.join(a.outdir, "fig6_11_transfer_rate.png"))


if __name__ == "__main__":
    fl.main_guard(main)
