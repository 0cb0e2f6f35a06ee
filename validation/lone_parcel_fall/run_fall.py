#!/usr/bin/env python3
"""A lone parcel falling from rest through still air (README.md beside this script).

Runs lone.toml for l = 1, 2, 3, with the air coupled one way (`air.feedback = false`: the
air does not feel the parcel) and two ways (the default), at three seeds (three start
positions in the 1.2 mm insertion cube, so three offsets from the grid), and, with
--grids, the two-way case on 1.2 mm cells too. From each run's energy.csv (momentum p_z
and potential energy, one row every 0.2 ms) it takes the parcel's speed after falls of
FALLS_MM and compares it with the single-particle equation of motion

    m dv/dt = m g (1 - rho_f / rho_p) - (1/2) rho_f C_D (pi d_O^2 / 4) v^2 l^3,
    C_D = 24/Re (1 + 0.15 Re^0.687),  Re = rho_f d_O v / mu_f,

i.e. one original particle (the parcel is l^3 of them side by side, each with its own
drag: the model's drag law at eps = 1, eqs. 8-11 of the paper), integrated here with
a 1e-7 s Runge-Kutta step.

Usage (from the repository root):
    /usr/bin/python3 validation/lone_parcel_fall/run_fall.py run   [--out out/lone_parcel_fall] [--grids]
    /usr/bin/python3 validation/lone_parcel_fall/run_fall.py check CGDEM WORKDIR   # the CI check
The run mode writes OUT/fall_table.csv and OUT/fall.png; the check mode runs the 0.6 mm
grid at one seed and asserts the tolerances of reference.toml, printing every error.
"""
import argparse
import math
import os
import shutil
import sys
import tomllib

import numpy as np
import pandas as pd

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "beverloo_discharge"))
import run_sweep as sweep  # noqa: E402
sys.path.insert(0, HERE)
import self_induced  # noqa: E402
CASE = os.path.join(HERE, "lone.toml")
G = 9.81
RHO_P, D_O = 1500.0, 125e-6          # Table 1
RHO_F, MU_F = 1.0, 1.8e-5            # Table 1
FALLS_MM = [3.5, 7.0, 10.0, 12.0, 15.0]
RATIOS = [1, 2, 3]
SEEDS = [1, 2, 3]


def ode_speed(falls_m, dt=1e-7):
    """Speed [m/s] of one original particle after each fall height, from rest in still air."""
    m = RHO_P * math.pi * D_O ** 3 / 6
    area = math.pi * D_O ** 2 / 4

    def acc(v):
        a = G * (1 - RHO_F / RHO_P)
        if v > 0:
            re = RHO_F * D_O * v / MU_F
            cd = 24 / re * (1 + 0.15 * re ** 0.687)
            a -= 0.5 * RHO_F * cd * area * v * v / m
        return a

    out, z, v = [], 0.0, 0.0
    for h in sorted(falls_m):
        while z < h:
            k1v, k1z = acc(v), v
            k2v, k2z = acc(v + dt / 2 * k1v), v + dt / 2 * k1v
            k3v, k3z = acc(v + dt / 2 * k2v), v + dt / 2 * k2v
            k4v, k4z = acc(v + dt * k3v), v + dt * k3v
            v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            z += dt / 6 * (k1z + 2 * k2z + 2 * k3z + k4z)
        out.append(v)
    return out


def run(cgdem, out, l, feedback, seed, dx=0.6e-3):
    """One run of lone.toml (kept when it has finished before), by run_sweep.run: one thread,
    its log beside its folder, a failure stops the script."""
    tag = f"l{l}_{'two' if feedback else 'one'}way_s{seed}" + ("" if dx == 0.6e-3 else f"_dx{dx * 1e3:.1f}mm")
    d = os.path.join(out, tag)
    sweep.run(cgdem, [CASE, "--set", f"particles.species[0].ratio={l}",
                      "--set", f"air.feedback={'true' if feedback else 'false'}", "--set", f"particles.seed={seed}",
                      "--set", f"air.dx={dx:.6g}"], d, d + ".log")
    return tag, d


def speeds(run_dir):
    """The parcel's downward speed after each fall of FALLS_MM (linear in the 0.2 ms rows)."""
    fall, vz, _ = self_induced.series(run_dir)
    if fall[-1] < FALLS_MM[-1] * 1e-3:
        sys.exit(f"{run_dir}: fell only {fall[-1] * 1e3:.1f} mm")
    return [float(np.interp(h * 1e-3, fall, vz)) for h in FALLS_MM]


def table(cgdem, out, seeds, grids):
    os.makedirs(out, exist_ok=True)
    ref = ode_speed([h * 1e-3 for h in FALLS_MM])
    rows = []
    runs = [(l, fb, s, 0.6e-3) for l in RATIOS for fb in (False, True) for s in seeds]
    if grids:
        runs += [(l, True, s, 1.2e-3) for l in RATIOS for s in seeds]
    for l, fb, s, dx in runs:
        tag, d = run(cgdem, out, l, fb, s, dx)
        for h, v, v0 in zip(FALLS_MM, speeds(d), ref):
            rows.append(dict(run=tag, l=l, coupling="two-way" if fb else "one-way", seed=s, dx_m=dx,
                             dx_over_d=dx / (l * D_O), fall_m=h * 1e-3, v_m_s=v, v_single_particle_m_s=v0,
                             rel_excess=v / v0 - 1))
    return pd.DataFrame(rows), ref


def summary(df):
    g = df.groupby(["l", "coupling", "dx_m", "fall_m"]).rel_excess
    s = pd.DataFrame(dict(mean=g.mean(), lo=g.min(), hi=g.max())).reset_index()
    return s


def plot(df, ref, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    h = np.array(FALLS_MM)
    hh = np.linspace(0.2, FALLS_MM[-1], 60)
    ax.plot(hh, ode_speed(list(hh * 1e-3)), "k-", label="one original particle (ODE)")
    ax.plot(hh, np.sqrt(2 * G * hh * 1e-3), "k:", label="vacuum")
    for (l, cpl, dx), g in df.groupby(["l", "coupling", "dx_m"]):
        m = g.groupby("fall_m").v_m_s.mean()
        style = dict(marker="o" if cpl == "two-way" else "x", ls="-" if cpl == "two-way" else "none",
                     color=f"C{l - 1}", alpha=1.0 if dx < 1e-3 else 0.5)
        ax.plot(h, m.values, label=f"l = {l}, {cpl}, dx {dx * 1e3:.1f} mm", **style)
    ax.set_xlabel("fall from rest [mm]")
    ax.set_ylabel("downward speed [m/s]")
    ax.set_title("A lone parcel falling through still air (d_O = 125 um)")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def check(cgdem, work):
    with open(os.path.join(HERE, "reference.toml"), "rb") as f:
        q = tomllib.load(f)["check"]
    shutil.rmtree(work, ignore_errors=True)  # never reuse the runs of an earlier build
    df, _ = table(cgdem, work, [1], grids=False)
    ok = True
    for r in df.itertuples():
        if r.coupling == "one-way":
            tol, what = q["one_way_tolerance"], "one-way"
        elif r.l == 1:
            tol, what = q["two_way_l1_tolerance"], "two-way, l = 1"
        else:
            tol, what = q["two_way_excess_max"], f"two-way, l = {r.l} (the known excess, bounded)"
        bad = abs(r.rel_excess) > tol if r.coupling == "one-way" or r.l == 1 else r.rel_excess > tol
        ok &= not bad
        print(f"{what}: fall {r.fall_m * 1e3:4.1f} mm, v = {r.v_m_s:.4f} m/s, single particle "
              f"{r.v_single_particle_m_s:.4f} m/s, error {r.rel_excess:+.4f} (tolerance {tol}){'  FAIL' if bad else ''}")
    # The self-induced velocity follows one law at every l (README.md, "How much air the
    # parcel drags along"): C = S rho_f dx^2 V / F in a band, and the same for every l.
    si = self_induced.measure(work, seeds=(1,))
    lo, hi, spread = q["self_induced_C_min"], q["self_induced_C_max"], q["self_induced_C_spread_max"]
    for h in (7e-3, 15e-3):
        rows = si[(si.fall_m - h).abs() < 1e-9]
        for r in rows.itertuples():
            bad = not lo <= r.C <= hi
            ok &= not bad
            print(f"self-induced velocity, l = {r.l}: fall {h * 1e3:4.1f} mm, S = {r.S_m_s * 1e3:.1f} mm/s "
                  f"({r.S_over_V:.3f} of V), C = {r.C:.3f} (band {lo}-{hi}){'  FAIL' if bad else ''}")
        ratio = rows.C.max() / rows.C.min()
        bad = len(rows) != len(RATIOS) or ratio > spread
        ok &= not bad
        print(f"self-induced velocity after {h * 1e3:.0f} mm: largest C / smallest C over l = {ratio:.3f} "
              f"(tolerance {spread}){'  FAIL' if bad else ''}")
    if not ok:
        sys.exit("lone parcel fall check failed")
    print("lone parcel fall check passed")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mode", choices=["run", "check"])
    p.add_argument("args", nargs="*")
    p.add_argument("--cgdem", default="build/cgdem")
    p.add_argument("--out", default="out/lone_parcel_fall")
    p.add_argument("--grids", action="store_true", help="also the two-way runs on 1.2 mm cells")
    a = p.parse_args()
    if a.mode == "check":
        check(*a.args)
        return
    df, ref = table(a.cgdem, a.out, SEEDS, a.grids)
    df.to_csv(os.path.join(a.out, "fall_table.csv"), index=False, float_format="%.6g")
    s = summary(df)
    print("single particle (ODE): " + ", ".join(f"{h} mm {v:.4f} m/s" for h, v in zip(FALLS_MM, ref)))
    for (l, cpl, dx), g in s.groupby(["l", "coupling", "dx_m"]):
        print(f"l = {l}, {cpl:7s}, dx {dx * 1e3:.1f} mm (dx/d {dx / (l * D_O):.1f}): excess "
              + ", ".join(f"{r.mean:+.3f} [{r.lo:+.3f}, {r.hi:+.3f}]" for r in g.itertuples()))
    plot(df, ref, os.path.join(a.out, "fall.png"))
    print(f"wrote {a.out}/fall_table.csv, fall.png")


if __name__ == "__main__":
    main()
