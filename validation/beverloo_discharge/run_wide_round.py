#!/usr/bin/env python3
"""Beverloo discharge beyond the 12 mm slab: wide slots and a round orifice.

wide   bin_wide_l3.toml, bin_wide_l2.toml, bin_wide_l1.toml: the slab bin 24 mm wide with an
       18 mm bed, slots up to 6 mm (16 parcel diameters at l = 3, 24 at l = 2, 48 original
       diameters). Measures how far l = 3 and l = 2 are from l = 2 and l = 1 at the widest
       slots (the 5 % question), and (b = 3.75 mm at l = 3, also run in the 12 mm bin) how
       much the bin's width changes the rate. l = 1 (127,000 particles) runs b = 6 mm only.
round  bin_orifice_l3.toml: a square 10 x 10 mm bin in 3D with a round hole of diameter D in
       its floor (a "ring" wall part), l = 3. Fits Beverloo's round-orifice law
           W = C rho_b sqrt(g) (D - k d)^(5/2)
       by least squares of W^(2/5) = a + s D (run_sweep.fit with power 2.5).

Each geometry is one fill (opening closed; settled.bin) and one discharge per opening
(--restart, the opening set with --set), one thread each, as in run_sweep.py; the rate is
the slope of the discharged mass over the steady window, its error from the window's
quarters (run_sweep.rate_of).

Usage (from the repository root):
    /usr/bin/python3 validation/beverloo_discharge/run_wide_round.py wide  [--ratios 3,2,1] [--out out/beverloo]
    /usr/bin/python3 validation/beverloo_discharge/run_wide_round.py round [--out out/beverloo]
    /usr/bin/python3 validation/beverloo_discharge/run_wide_round.py round16   # the 16 mm bin, D = 3 mm
    /usr/bin/python3 validation/beverloo_discharge/run_wide_round.py analyse [--out out/beverloo]
Writes OUT/wide_table.csv, OUT/round_table.csv, OUT/round_fit.csv and OUT/beverloo_wide_round.png.
"""
import argparse
import math
import os
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_sweep as rs  # noqa: E402

HERE = rs.HERE
WIDE_X_C, WIDE_W = 12e-3, 24e-3                  # m: the wide bin's slot centre and inner width
WIDE_SLOTS_MM = {3: [3.75, 4.5, 6.0], 2: [4.5, 6.0], 1: [6.0]}
ROUND_D_MM = [1.875, 2.25, 2.625, 3.0]            # D = 5, 6, 7, 8 parcel diameters at l = 3
ROUND_BIN = (0.0, 10e-3)                          # m: the round bin's walls, along x and y
ROUND_WINDOW = (0.03, 0.10)                       # s
CLOSED_RADIUS = 1e-6                              # m: the hole during the fill
BIG_ROUND_BIN, BIG_ROUND_D_MM = 16e-3, 3.0          # m, mm: the bin-size check (D = 8 d)
BEVERLOO_ROUND = dict(C=0.58, k=1.5)              # Beverloo et al. (1961), as quoted in issue #17


def wide_sets(b):
    return ["--set", f"walls.body[0].part[2].max=[{WIDE_X_C - b / 2:.6g},2.5e-3,{rs.FLOOR_TOP:.6g}]",
            "--set", f"walls.body[0].part[3].min=[{WIDE_X_C + b / 2:.6g},-1e-3,-1e-3]"]


def round_sets(D):
    return ["--set", f"walls.body[0].part[4].radius_inner={D / 2:.6g}"]


def bigger_round_bin(w):
    """--set arguments that make bin_orifice_l3.toml's bin w x w (m) with the same 10 mm bed
    and the hole at its centre: the check that the 10 mm bin's walls do not set the rate."""
    c, e = w / 2, w + 1e-3
    return ["--set", f"domain.max=[{w + 0.5e-3:.6g},{w + 0.5e-3:.6g},26e-3]",
            "--set", f"particles.insert[0].max=[{w:.6g},{w:.6g},24.5e-3]",
            "--set", f"particles.insert[0].solid_volume={0.6 * w * w * 10e-3:.6g}",
            "--set", f"walls.body[0].part[0].max=[0.0,{e:.6g},30e-3]",
            "--set", f"walls.body[0].part[1].min=[{w:.6g},-1e-3,-1e-3]",
            "--set", f"walls.body[0].part[1].max=[{e:.6g},{e:.6g},30e-3]",
            "--set", f"walls.body[0].part[2].max=[{e:.6g},0.0,30e-3]",
            "--set", f"walls.body[0].part[3].min=[-1e-3,{w:.6g},-1e-3]",
            "--set", f"walls.body[0].part[3].max=[{e:.6g},{e:.6g},30e-3]",
            "--set", f"walls.body[0].part[4].p0=[{c:.6g},{c:.6g},0.0]",
            "--set", f"walls.body[0].part[4].p1=[{c:.6g},{c:.6g},0.5e-3]",
            "--set", f"walls.body[0].part[4].radius_outer={0.75 * w:.6g}"]


def run_wide(cgdem, out, ratios):
    for l in ratios:
        case = os.path.join(HERE, f"bin_wide_l{l}.toml")
        f = os.path.join(out, f"wide_fill_l{l}")
        rs.run(cgdem, [case, "--set", "time.end=0.0", *wide_sets(0.0)], f, f + ".log")
        for b_mm in WIDE_SLOTS_MM[l]:
            d = os.path.join(out, f"wide_l{l}_b{b_mm:.3f}mm")
            rs.run(cgdem, [case, "--restart", os.path.join(f, "settled.bin"), *wide_sets(b_mm * 1e-3)], d, d + ".log")


def run_round(cgdem, out):
    case = os.path.join(HERE, "bin_orifice_l3.toml")
    f = os.path.join(out, "round_fill_l3")
    rs.run(cgdem, [case, "--set", "time.end=0.0", *round_sets(2 * CLOSED_RADIUS)], f, f + ".log")
    for D_mm in ROUND_D_MM:
        d = os.path.join(out, f"round_l3_D{D_mm:.3f}mm")
        rs.run(cgdem, [case, "--restart", os.path.join(f, "settled.bin"), *round_sets(D_mm * 1e-3)], d, d + ".log")


def run_round_bigger(cgdem, out):
    case = os.path.join(HERE, "bin_orifice_l3.toml")
    big = bigger_round_bin(BIG_ROUND_BIN)
    f = os.path.join(out, "round16_fill_l3")
    rs.run(cgdem, [case, *big, "--set", "time.end=0.0", *round_sets(2 * CLOSED_RADIUS)], f, f + ".log")
    d = os.path.join(out, f"round16_l3_D{BIG_ROUND_D_MM:.3f}mm")
    rs.run(cgdem, [case, *big, "--restart", os.path.join(f, "settled.bin"), *round_sets(BIG_ROUND_D_MM * 1e-3)], d,
           d + ".log")


def analyse_wide(out):
    rows = []
    for l, slots in WIDE_SLOTS_MM.items():
        f = os.path.join(out, f"wide_fill_l{l}")
        if not os.path.isdir(f):
            continue
        rho_b, phi, top = rs.bulk_density(f, bin_x=(0.0, WIDE_W))
        for b_mm in slots:
            d = os.path.join(out, f"wide_l{l}_b{b_mm:.3f}mm")
            if not os.path.exists(os.path.join(d, "metrics.csv")):
                continue
            r = rs.rate_of(d)
            r.pop("t"), r.pop("M")
            rows.append(dict(l=l, bin_width_m=WIDE_W, bed_height_m=top + r["d_m"] / 2 - rs.FLOOR_TOP, rho_b_kg_m3=rho_b,
                             phi=phi, b_m=b_mm * 1e-3, b_over_d=b_mm * 1e-3 / r["d_m"], window_t0_s=rs.WINDOW[0],
                             window_t1_s=rs.WINDOW[1], **r))
    df = pd.DataFrame(rows)
    if df.empty:
        return df
    df.to_csv(os.path.join(out, "wide_table.csv"), index=False, float_format="%.6g")
    print(df[["l", "b_m", "b_over_d", "W_per_L_kg_s_m", "W_per_L_err_kg_s_m", "drift", "parcels_in_window",
              "discharged_fraction_at_end", "rho_b_kg_m3", "bed_height_m"]].to_string(index=False))
    narrow = os.path.join(out, "beverloo_table.csv")
    if os.path.exists(narrow):
        n = pd.read_csv(narrow)
        for r in df.itertuples():
            m = n[(n.l == r.l) & (n.fill == "full") & np.isclose(n.b_m, r.b_m)]
            if len(m):
                print(f"bin width, l = {r.l}, b = {r.b_m * 1e3:.3f} mm: 12 mm bin {m.iloc[0].W_per_L_kg_s_m:.4g}, "
                      f"24 mm bin {r.W_per_L_kg_s_m:.4g} kg/s/m ({r.W_per_L_kg_s_m / m.iloc[0].W_per_L_kg_s_m - 1:+.3f})")
    for coarse, fine in ((3, 2), (2, 1), (3, 1)):
        for r in df[df.l == coarse].itertuples():
            f = df[(df.l == fine) & np.isclose(df.b_m, r.b_m)]
            if len(f):
                rel = r.W_per_L_kg_s_m / f.iloc[0].W_per_L_kg_s_m - 1
                err = math.hypot(r.W_per_L_err_kg_s_m / r.W_per_L_kg_s_m,
                                 f.iloc[0].W_per_L_err_kg_s_m / f.iloc[0].W_per_L_kg_s_m)
                print(f"wide bin, l = {coarse} vs l = {fine}, b = {r.b_m * 1e3:.3f} mm (b/d = {r.b_over_d:.1f} at "
                      f"l = {coarse}, {f.iloc[0].b_over_d:.1f} at l = {fine}): {rel:+.3f} +- {err:.3f}")
    return df


def round_row(run_dir, bin_width, D_mm, rho_b, phi, top):
    """The table row of one round-orifice discharge: its rate over ROUND_WINDOW (the slot's
    per-length figures left out) beside its bin's settled bed."""
    r = rs.rate_of(run_dir, window=ROUND_WINDOW)
    for k in ("t", "M", "L_m", "W_per_L_kg_s_m", "W_per_L_err_kg_s_m"):
        r.pop(k)
    return dict(l=3, bin_width_m=bin_width, bed_height_m=top + r["d_m"] / 2 - rs.FLOOR_TOP, rho_b_kg_m3=rho_b, phi=phi,
                D_m=D_mm * 1e-3, D_over_d=D_mm * 1e-3 / r["d_m"], window_t0_s=ROUND_WINDOW[0],
                window_t1_s=ROUND_WINDOW[1], **r)


def analyse_round(out):
    f = os.path.join(out, "round_fill_l3")
    if not os.path.isdir(f):
        return pd.DataFrame(), None
    rho_b, phi, top = rs.bulk_density(f, bin_x=ROUND_BIN, bin_y=ROUND_BIN)
    rows = []
    for D_mm in ROUND_D_MM:
        d = os.path.join(out, f"round_l3_D{D_mm:.3f}mm")
        if os.path.exists(os.path.join(d, "metrics.csv")):
            rows.append(round_row(d, ROUND_BIN[1] - ROUND_BIN[0], D_mm, rho_b, phi, top))
    if len(rows) < 3:
        return pd.DataFrame(rows), None
    v = rs.fit(rows, width="D_m", rate="W_kg_s", power=2.5)
    big = os.path.join(out, f"round16_l3_D{BIG_ROUND_D_MM:.3f}mm")
    if os.path.exists(os.path.join(big, "metrics.csv")):
        rho16, phi16, top16 = rs.bulk_density(os.path.join(out, "round16_fill_l3"), bin_x=(0.0, BIG_ROUND_BIN),
                                              bin_y=(0.0, BIG_ROUND_BIN))
        r = round_row(big, BIG_ROUND_BIN, BIG_ROUND_D_MM, rho16, phi16, top16)
        rows.append(r)
        small = [x for x in rows if x["bin_width_m"] < BIG_ROUND_BIN and math.isclose(x["D_m"], BIG_ROUND_D_MM * 1e-3)]
        if small:
            print(f"bin size, round orifice D = {BIG_ROUND_D_MM} mm: 10 mm bin W = {small[0]['W_kg_s']:.4g}, 16 mm bin "
                  f"{r['W_kg_s']:.4g} kg/s ({r['W_kg_s'] / small[0]['W_kg_s'] - 1:+.3f}; rho_b {small[0]['rho_b_kg_m3']:.0f}"
                  f" and {rho16:.0f} kg/m^3)")
    df = pd.DataFrame(rows)
    df["own_fit_W_kg_s"] = [v["s"] ** 2.5 * max(r.D_m + v["a"] / v["s"], 0) ** 2.5 for r in df.itertuples()]
    df["beverloo_C058_k15_W_kg_s"] = [BEVERLOO_ROUND["C"] * r.rho_b_kg_m3 * math.sqrt(rs.G)
                                      * max(r.D_m - BEVERLOO_ROUND["k"] * r.d_m, 0) ** 2.5 for r in df.itertuples()]
    df.to_csv(os.path.join(out, "round_table.csv"), index=False, float_format="%.6g")
    pd.DataFrame([dict(l=3, orifices=len(rows), **v)]).to_csv(os.path.join(out, "round_fit.csv"), index=False,
                                                             float_format="%.6g")
    print(df[["bin_width_m", "D_m", "D_over_d", "W_kg_s", "W_err_kg_s", "drift", "parcels_in_window", "discharged_fraction_at_end",
              "rho_b_kg_m3", "bed_height_m", "own_fit_W_kg_s", "beverloo_C058_k15_W_kg_s"]].to_string(index=False))
    print(f"round orifice, l = 3: C = {v['C']:.3f} +- {v['C_err']:.3f}, k = {v['k']:.3f} +- {v['k_err']:.3f} "
          f"({v['n']} orifices, rms relative misfit of W {v['rms_rel']:.3f}); Beverloo: C ~ 0.58, k ~ 1.4-1.5")
    return df, v


def plot(out, wide, rnd, v):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.4))
    narrow = os.path.join(out, "beverloo_table.csv")
    n = pd.read_csv(narrow) if os.path.exists(narrow) else pd.DataFrame()
    colours = {3: "C0", 2: "C1", 1: "C2"}
    for l in (3, 2, 1):
        if len(n):
            r = n[(n.l == l) & (n.fill == "full")]
            ax[0].plot(r.b_m * 1e3, r.W_per_L_kg_s_m ** (2 / 3), "o", mfc="none", color=colours[l],
                       label=f"l = {l}, 12 mm bin")
        if len(wide):
            r = wide[wide.l == l]
            if len(r):
                ax[0].errorbar(r.b_m * 1e3, r.W_per_L_kg_s_m ** (2 / 3),
                               yerr=(2 / 3) * r.W_per_L_kg_s_m ** (-1 / 3) * r.W_per_L_err_kg_s_m, fmt="s",
                               color=colours[l], label=f"l = {l}, 24 mm bin")
    ax[0].set(xlabel="slot width b [mm]", ylabel="(W/L)^(2/3) [(kg/s/m)^(2/3)]", title="slots: both bins")
    ax[0].set_xlim(left=0)
    ax[0].set_ylim(bottom=0)
    ax[0].legend(fontsize=7)
    if len(rnd):
        for w, g in rnd.groupby("bin_width_m"):
            ax[1].errorbar(g.D_m * 1e3, g.W_kg_s ** 0.4, yerr=0.4 * g.W_kg_s ** (-0.6) * g.W_err_kg_s,
                           fmt="o" if w < BIG_ROUND_BIN else "s", color="C0" if w < BIG_ROUND_BIN else "C3",
                           label=f"l = 3, round orifice, {w * 1e3:.0f} mm bin")
        DD = np.linspace(0, rnd.D_m.max() * 1.1, 200)
        if v:
            ax[1].plot(DD * 1e3, np.maximum(v["a"] + v["s"] * DD, 0), color="C0",
                       label=f"fit: C = {v['C']:.2f}+-{v['C_err']:.2f}, k = {v['k']:.2f}+-{v['k_err']:.2f}")
        rho_b, d = rnd.rho_b_kg_m3.iloc[0], rnd.d_m.iloc[0]
        ax[1].plot(DD * 1e3, (BEVERLOO_ROUND["C"] * rho_b * math.sqrt(rs.G)) ** 0.4 * np.maximum(DD - BEVERLOO_ROUND["k"] * d, 0),
                   "k--", label="Beverloo C = 0.58, k = 1.5")
    ax[1].set(xlabel="orifice diameter D [mm]", ylabel="W^(2/5) [(kg/s)^(2/5)]",
              title="round orifice: W^(2/5) = (C rho_b g^0.5)^(2/5) (D - k d)")
    ax[1].set_xlim(left=0)
    ax[1].set_ylim(bottom=0)
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "beverloo_wide_round.png"), dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("what", choices=["wide", "round", "round16", "analyse"])
    p.add_argument("--cgdem", default="build/cgdem")
    p.add_argument("--out", default="out/beverloo")
    p.add_argument("--ratios", default="3,2", help="wide: the ratios to run")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.what == "wide":
        run_wide(a.cgdem, a.out, [int(x) for x in a.ratios.split(",")])
    elif a.what == "round":
        run_round(a.cgdem, a.out)
    elif a.what == "round16":
        run_round_bigger(a.cgdem, a.out)
    wide = analyse_wide(a.out)
    rnd, v = analyse_round(a.out)
    plot(a.out, wide, rnd, v)


if __name__ == "__main__":
    main()
