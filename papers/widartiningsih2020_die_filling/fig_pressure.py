#!/usr/bin/python3
"""Figs. 7 and 12 of the paper: gauge air pressure averaged over the measurement cells
A, B and C in the die, for both die types.

Reads, per run: config.resolved.toml and diagnostics.csv (columns p_A_Pa, p_B_Pa, p_C_Pa: the
pressure minus the still-air hydrostatic pressure, averaged over the air cells of each box,
one row every 0.1 ms). Where the cells are: README of validation/die_filling (A above the
shallow floor, B above the deep floor, C in the deep section just below the table top; the
paper does not give their positions). Only t >= 0 is drawn. Grey dotted lines: the times
the paper discusses (die opening ~0.05 s, broad maximum ~0.10 s, die closing ~0.25 s);
dashed: the sharp peak from entrapped air (~0.19 s type 1, ~0.18 s type 2). The paper gives
no pressure values in its text. Rows: cells A, B, C; columns: die types.

  fig7_12_pressure.png
"""
import os

import figlib as fl
from figlib import plt

CELLS = ("A", "B", "C")


def main():
    a = fl.arg_parser(__doc__.split("\n\n")[0]).parse_args()
    groups = fl.by_die_type(fl.load_runs(a.runs))
    fig, axes = plt.subplots(len(CELLS), len(groups), figsize=(4.2 * len(groups), 6.6), squeeze=False,
                             sharex=True)
    for c, (die_type, runs) in enumerate(groups.items()):
        series = []
        for run in runs:
            d = run.diagnostics()
            keep = d["t_s"] >= 0
            if not keep.any():
                raise fl.InputError(f"{run.dir}/diagnostics.csv: no rows at t >= 0 yet")
            for cell in CELLS:
                if f"p_{cell}_Pa" not in d:
                    raise fl.InputError(f"{run.dir}/diagnostics.csv: no column p_{cell}_Pa (run without air?)")
            series.append((run, d["t_s"][keep], {cell: d[f"p_{cell}_Pa"][keep] for cell in CELLS}))
        tp = fl.PAPER[die_type]["peak_time"]
        for r, cell in enumerate(CELLS):
            ax = axes[r, c]
            for name, te in fl.PAPER_PRESSURE_EVENTS.items():
                ax.axvline(te, color="0.5", ls=":", lw=0.8)
            ax.axvline(tp, color="k", ls="--", lw=0.8, label=f"paper: entrapped-air peak ~{tp:.2f} s" if r == 0 else None)
            for run, t, p in series:
                ax.plot(t, p[cell], color=run.colour, lw=0.6, label=run.label if r == 0 else None)
            ax.axhline(0, color="0.6", lw=0.5)
            ax.set_ylabel(f"cell {cell}: gauge p [Pa]", fontsize=8)
            ax.tick_params(labelsize=7)
            ax.set_xlim(0, 0.30)
            if r == 0:
                ax.set_title(f"Die type {die_type} [cf. paper Fig. {7 if die_type == 1 else 12}]; "
                             "dotted: 0.05, 0.10, 0.25 s", fontsize=8)
                ax.legend(fontsize=6, loc="upper left", frameon=False)
        axes[-1, c].set_xlabel("time t [s] (shoe starts at 0)", fontsize=8)
    fig.tight_layout()
    fl.save(fig, os.path.join(a.outdir, "fig7_12_pressure.png"))


if __name__ == "__main__":
    fl.main_guard(main)
