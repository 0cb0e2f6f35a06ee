#!/usr/bin/env python3
"""How much air a lone parcel drags along: its self-induced velocity, from run_fall.py's runs.

In still air the air velocity a falling parcel reads at its own position is entirely its own
disturbance S (the air its drag pushed down through the kernel's cells). For each two-way
run of `run_fall.py run --grids` this script takes, after each fall height,
  V  the parcel's speed and F = m (g - dV/dt) the air's force on it (energy.csv: p_z every
     0.2 ms, central differences),
  W  the slip that gives the force F in the ONE-way run of the same l and seed (the air
     there does not move, so that run is the model's F(slip) at the parcel's own eps),
  S = V - W, the part of the speed the drag did not see,
and prints S, S/V and C = S rho_f dx^2 V / F, the self-induced velocity in units of the
momentum the parcel hands to the air per cell area and fall speed (a parcel that crosses a
cell of width dx in dx/V deposits F dx/V there; spread over a cell's air, rho_f dx^3, that
is F/(rho_f dx^2 V)). Beside it `G c` = 0.564 l^3 d_O/dx, the steady Stokes estimate of the
self-induced velocity over the slip for a point force smeared with the kernel's width
(Gaussian sigma = dx/2, read back through the same kernel): the slow-motion limit.

Usage (from the repository root):
    /usr/bin/python3 validation/lone_parcel_fall/self_induced.py OUT [--csv FILE]
OUT is run_fall.py's --out folder (default out/lone_parcel_fall), after `run --grids`.
"""
import argparse
import os
import sys

import numpy as np
import pandas as pd

G = 9.81
RHO_F = 1.0
D_O = 125e-6
FALLS_MM = [3.5, 7.0, 10.0, 15.0]


def series(d):
    """The run's fall [m], downward speed [m/s] and the air's upward force on the parcel [N],
    one value per energy.csv row; stops if the parcel left the box."""
    e = pd.read_csv(os.path.join(d, "energy.csv"), comment="#")
    if int(e.particles.iloc[-1]) != 1:
        sys.exit(f"{d}: the parcel left the box")
    m = float(e.mass_kg.iloc[0])
    t = e.t_s.to_numpy()
    v = (-e.pz_kg_m_s / m).to_numpy()
    fall = ((e.E_pot_J.iloc[0] - e.E_pot_J) / (m * G)).to_numpy()
    force = m * (G - np.gradient(v, t))
    return fall, v, force


def measure(out, ratios=(1, 2, 3), seeds=(1, 2, 3)):
    """One row per two-way run of run_fall.py in OUT and fall height (see the module text)."""
    rows = []
    for l in ratios:
        for dx, suffix in ((0.6e-3, ""), (1.2e-3, "_dx1.2mm")):
            for seed in seeds:
                one = os.path.join(out, f"l{l}_oneway_s{seed}")
                two = os.path.join(out, f"l{l}_twoway_s{seed}{suffix}")
                if not (os.path.isdir(one) and os.path.isdir(two)):
                    continue
                f1, v1, F1 = series(one)
                f2, v2, F2 = series(two)
                order = np.argsort(F1[5:]) + 5  # F(slip) of the one-way run, without the start-up rows
                for h in FALLS_MM:
                    if f2[-1] < h * 1e-3:
                        sys.exit(f"{two}: fell only {f2[-1] * 1e3:.1f} mm")
                    V = float(np.interp(h * 1e-3, f2, v2))
                    F = float(np.interp(h * 1e-3, f2, F2))
                    W = float(np.interp(F, F1[order], v1[order]))
                    S = V - W
                    rows.append(dict(l=l, dx_m=dx, seed=seed, fall_m=h * 1e-3, V_m_s=V, F_N=F, W_m_s=W, S_m_s=S,
                                     S_over_V=S / V, C=S * RHO_F * dx * dx * V / F,
                                     Gc_stokes=0.564 * l ** 3 * D_O / dx))
    return pd.DataFrame(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default="out/lone_parcel_fall")
    ap.add_argument("--csv", help="also write the table here")
    a = ap.parse_args()
    df = measure(a.out)
    if df.empty:
        sys.exit(f"{a.out}: no runs of run_fall.py there (run it with --grids first)")
    mean = df.groupby(["l", "dx_m", "fall_m"], as_index=False).agg(
        V=("V_m_s", "mean"), S=("S_m_s", "mean"), S_over_V=("S_over_V", "mean"), C=("C", "mean"),
        C_range=("C", lambda c: c.max() - c.min()), Gc=("Gc_stokes", "first"))
    print("| l | dx [mm] | fall [mm] | V [m/s] | S [mm/s] | S/V | C = S rho dx^2 V / F | seeds' range of C | Stokes G c |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in mean.itertuples():
        print(f"| {r.l} | {r.dx_m * 1e3:.1f} | {r.fall_m * 1e3:.1f} | {r.V:.3f} | {r.S * 1e3:.1f} | {r.S_over_V:.3f} | "
              f"{r.C:.3f} | {r.C_range:.3f} | {r.Gc:.2f} |")
    if a.csv:
        df.to_csv(a.csv, index=False, float_format="%.6g")


if __name__ == "__main__":
    main()
