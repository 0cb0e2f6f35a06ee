#!/usr/bin/env python3
"""Beverloo discharge sweep: runs the fills and the slot discharges, fits C' and k.

For each ratio l (case bin_l<l>.toml beside this script):
  fill       t = -0.10..0 s, slot closed (the floor plates meet at x = 6 mm); settled.bin
  discharge  --restart fill/settled.bin, slot of width b open, t = 0..0.08 s
and, at l = 3, a fill of half the height with one discharge (b = 2.25 mm), to check that the
rate does not depend on the fill height.

The discharged mass M(t) is energy.csv's `removed` (parcels whose centre passed the floor's
underside z = 0 and left the domain) times the parcel mass rho_p pi (l d_O)^3 / 6. The rate
W is the least-squares slope of M(t) over the steady window [0.03, 0.08] s; its uncertainty
is the standard error of the slopes of the window's four quarters; `drift` is the relative
difference of the last and the first half's slopes.

Beverloo et al. (1961), slot form per unit length L of the slot:
    W / L = C' rho_b sqrt(g) (b - k d)^(3/2)                               (slot law)
so (W/L)^(2/3) = (C' rho_b sqrt(g))^(2/3) (b - k d) is linear in b: least squares
y = a + s b gives k = -a / (s d), C' = s^(3/2) / (rho_b sqrt(g)), with d the PARCEL diameter
l d_O and rho_b the settled bed's bulk density (from the fill's snapshot at t = 0).

Usage (from the repository root; one thread, runs one after another):
    /usr/bin/python3 validation/beverloo_discharge/run_sweep.py --ratios 3,2 [--out out/beverloo]
    /usr/bin/python3 validation/beverloo_discharge/run_sweep.py --analyse-only
Writes OUT/beverloo_table.csv, OUT/beverloo_fit.csv and OUT/beverloo.png.
"""
import argparse
import glob
import math
import os
import subprocess
import sys
import time
import tomllib

import h5py
import numpy as np
import pandas as pd

HERE = os.path.dirname(os.path.abspath(__file__))
D_O = 125e-6          # m, original particle (Table 1 of the paper)
G = 9.81              # m/s^2
X_C = 6e-3            # m, the slot's centre
FLOOR_TOP = 0.5e-3    # m, the floor's top; its underside is z = 0
BIN_W = 12e-3         # m, the bin's inner width
SLOTS_MM = [1.125, 1.5, 1.875, 2.25, 3.0, 3.75]   # b: 3, 4, 5, 6, 8, 10 parcel diameters at l = 3
HEIGHT_CHECK_MM = 2.25
WINDOW = (0.03, 0.08)  # s, the steady window (the rate still rises by ~5 % until 0.03 s)
T_END = 0.08           # s
AGREE = 0.05           # coarse vs finer: relative difference of W/L


def slot_sets(b):
    """--set arguments that open a slot of width b (m) between the two floor plates."""
    return ["--set", f"walls.body[0].part[2].max=[{X_C - b / 2:.6g},2.5e-3,{FLOOR_TOP:.6g}]",
            "--set", f"walls.body[0].part[3].min=[{X_C + b / 2:.6g},-1e-3,-1e-3]"]


def case_of(l):
    return os.path.join(HERE, f"bin_l{l}.toml")


def run(cgdem, args, out, log):
    if os.path.exists(os.path.join(out, "metrics.csv")):
        print(f"  {out}: done before, kept")
        return
    cmd = [cgdem, "run", *args, "--threads", "1", "--output", out]
    t0 = time.time()
    with open(log, "w") as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env={**os.environ, "OMP_NUM_THREADS": "1"})
    if rc != 0:
        sys.exit(f"run failed ({rc}): {' '.join(cmd)}; see {log}")
    print(f"  {out}: {time.time() - t0:.0f} s wall")


def fill_dir(out, l, tag=""):
    return os.path.join(out, f"fill_l{l}{tag}")


def discharge_dir(out, l, b, tag=""):
    return os.path.join(out, f"l{l}_b{b * 1e3:.3f}mm{tag}")


def run_all(cgdem, out, ratios, slots):
    os.makedirs(out, exist_ok=True)
    for l in ratios:
        case = case_of(l)
        fills = [("", [])]
        if l == 3:
            fills.append(("_half", ["--set", "particles.insert[0].solid_volume=72e-9"]))
        for tag, extra in fills:
            f = fill_dir(out, l, tag)
            run(cgdem, [case, "--set", "time.end=0.0", *slot_sets(0.0), *extra], f, f + ".log")
            for b_mm in (slots if tag == "" else [HEIGHT_CHECK_MM]):
                b = b_mm * 1e-3
                d = discharge_dir(out, l, b, tag)
                run(cgdem, [case, "--restart", os.path.join(f, "settled.bin"), "--set", f"time.end={T_END}",
                            *slot_sets(b), *extra], d, d + ".log")


def resolved(run_dir):
    with open(os.path.join(run_dir, "config.resolved.toml"), "rb") as f:
        return tomllib.load(f)


def bulk_density(fill, bin_x=(0.0, BIN_W), bin_y=None):
    """rho_b of the settled bed: solid volume of the parcels whose centres lie in a box
    1 mm from the side walls and 1.5 mm from the floor and from the bed's surface. The walls
    are at x = bin_x; along y the slab's period, or, for a 3D bin, 1 mm from y = bin_y."""
    snap = sorted(glob.glob(os.path.join(fill, "particles_*.h5")))[-1]
    with h5py.File(snap) as h:
        x = h["particles/x"][:]
        dd = h["particles/d"][:]
    cfg = resolved(fill)
    rho_p = cfg["particles"]["species"][0]["density"]
    if bin_y is None:
        L = cfg["domain"]["max"][1] - cfg["domain"]["min"][1]
        in_y = np.ones(len(x), bool)
    else:
        L = bin_y[1] - bin_y[0] - 2e-3
        in_y = (x[:, 1] > bin_y[0] + 1e-3) & (x[:, 1] < bin_y[1] - 1e-3)
    top = np.percentile(x[:, 2], 99)
    lo, hi = FLOOR_TOP + 1.5e-3, top - 1.5e-3
    inside = (x[:, 0] > bin_x[0] + 1e-3) & (x[:, 0] < bin_x[1] - 1e-3) & in_y & (x[:, 2] > lo) & (x[:, 2] < hi)
    phi = np.sum(np.pi / 6 * dd[inside] ** 3) / ((bin_x[1] - bin_x[0] - 2e-3) * L * (hi - lo))
    return phi * rho_p, phi, top


def rate_of(run_dir, window=None):
    """The discharge rate of a run over `window` (s, s; default the module's WINDOW, read at
    the call, so a check that sets run_sweep.WINDOW gets its own)."""
    window = window or WINDOW
    cfg = resolved(run_dir)
    sp = cfg["particles"]["species"][0]
    d = sp["ratio"] * sp["d_original"]
    m_p = sp["density"] * np.pi / 6 * d ** 3
    L = cfg["domain"]["max"][1] - cfg["domain"]["min"][1]
    e = pd.read_csv(os.path.join(run_dir, "energy.csv"), comment="#")
    t, M = e["t_s"].to_numpy(), e["removed"].to_numpy() * m_p
    w = (t >= window[0] - 1e-9) & (t <= window[1] + 1e-9)
    W = np.polyfit(t[w], M[w], 1)[0]
    edges = np.linspace(window[0], window[1], 5)
    quarters = [np.polyfit(t[(t >= a - 1e-9) & (t <= b + 1e-9)], M[(t >= a - 1e-9) & (t <= b + 1e-9)], 1)[0]
                for a, b in zip(edges[:-1], edges[1:])]
    mid = 0.5 * (window[0] + window[1])
    first = np.polyfit(t[w & (t <= mid + 1e-9)], M[w & (t <= mid + 1e-9)], 1)[0]
    last = np.polyfit(t[w & (t >= mid - 1e-9)], M[w & (t >= mid - 1e-9)], 1)[0]
    n0 = e["particles"].iloc[0] + e["removed"].iloc[0]
    return dict(d_m=d, L_m=L, m_parcel_kg=m_p, W_kg_s=W, W_err_kg_s=np.std(quarters, ddof=1) / 2,
                W_per_L_kg_s_m=W / L, W_per_L_err_kg_s_m=np.std(quarters, ddof=1) / 2 / L,
                drift=(last - first) / W if W > 0 else float("nan"),
                parcels_in_window=int(round(W * (window[1] - window[0]) / m_p)),
                discharged_fraction_at_end=float(e["removed"].iloc[-1] / n0), t=t, M=M)


def fit(rows, width="b_m", rate="W_per_L_kg_s_m", power=1.5):
    """Least squares of rate^(1/power) = a + s width (the slot: (W/L)^(2/3) = a + s b; the
    round orifice: W^(2/5) = a + s D with power 2.5); returns C (C'), k and their standard
    errors."""
    b = np.array([r[width] for r in rows])
    y = np.array([r[rate] for r in rows]) ** (1 / power)
    X = np.column_stack([np.ones_like(b), b])
    coef, res, *_ = np.linalg.lstsq(X, y, rcond=None)
    a, s = coef
    dof = len(b) - 2
    s2 = float(np.sum((y - X @ coef) ** 2)) / dof
    cov = s2 * np.linalg.inv(X.T @ X)
    d, rho_b = rows[0]["d_m"], rows[0]["rho_b_kg_m3"]
    k = -a / (s * d)
    C = s ** power / (rho_b * math.sqrt(G))
    gk = np.array([-1 / (s * d), a / (s ** 2 * d)])
    gC = np.array([0.0, power * s ** (power - 1) / (rho_b * math.sqrt(G))])
    return dict(C=C, C_err=math.sqrt(gC @ cov @ gC), k=k, k_err=math.sqrt(gk @ cov @ gk), a=a, s=s,
                rms_rel=float(np.sqrt(np.mean(((X @ coef) ** power / y ** power - 1) ** 2))), n=len(b))


def analyse(out, ratios):
    table, series, fits = [], {}, {}
    for l in ratios:
        for tag in ["", "_half"]:
            f = fill_dir(out, l, tag)
            if not os.path.isdir(f):
                continue
            rho_b, phi, top = bulk_density(f)
            for b_mm in SLOTS_MM:
                dd = discharge_dir(out, l, b_mm * 1e-3, tag)
                if not os.path.exists(os.path.join(dd, "metrics.csv")):
                    continue
                r = rate_of(dd)
                series[(l, b_mm, tag)] = (r.pop("t"), r.pop("M"))
                table.append(dict(l=l, fill="half" if tag else "full", bed_height_m=top + r["d_m"] / 2 - FLOOR_TOP,
                                  rho_b_kg_m3=rho_b, phi=phi, b_m=b_mm * 1e-3, b_over_d=b_mm * 1e-3 / r["d_m"],
                                  window_t0_s=WINDOW[0], window_t1_s=WINDOW[1], **r))
    df = pd.DataFrame(table)
    for l in ratios:
        rows = [r for r in table if r["l"] == l and r["fill"] == "full" and r["W_kg_s"] > 0]
        if len(rows) >= 3:
            fits[l] = fit(rows)
    if df.empty:
        sys.exit(f"no finished runs in {out}")
    # The same fit on the b/d range every fitted ratio covers (the form is not exact over
    # b/d = 3..15: C' and k grow with the range's b/d).
    # Each pair of neighbouring ratios (3 and 2, 2 and 1) on the b/d range both cover.
    common = {}
    fitted = sorted(fits, reverse=True)
    for coarse, fine in zip(fitted, fitted[1:]):
        lo = max(min(r["b_over_d"] for r in table if r["l"] == l) for l in (coarse, fine)) - 1e-9
        hi = min(max(r["b_over_d"] for r in table if r["l"] == l) for l in (coarse, fine)) + 1e-9
        for l in (coarse, fine):
            rows = [r for r in table if r["l"] == l and r["fill"] == "full" and lo <= r["b_over_d"] <= hi]
            if len(rows) >= 3:
                common[(l, coarse + fine - l)] = dict(fit(rows), b_over_d_min=lo, b_over_d_max=hi)
    df["beverloo_fit_W_per_L_kg_s_m"] = [
        fits[r.l]["s"] ** 1.5 * max(r.b_m + fits[r.l]["a"] / fits[r.l]["s"], 0) ** 1.5 if r.l in fits else np.nan
        for r in df.itertuples()]
    ref_l = max(fits) if fits else None
    df["law_of_l%s_fit_W_per_L_kg_s_m" % ref_l] = [
        fits[ref_l]["C"] * r.rho_b_kg_m3 * math.sqrt(G) * max(r.b_m - fits[ref_l]["k"] * r.d_m, 0) ** 1.5
        if ref_l else np.nan for r in df.itertuples()]
    df.to_csv(os.path.join(out, "beverloo_table.csv"), index=False, float_format="%.6g")
    pd.DataFrame([dict(l=l, slots="all", **v) for l, v in fits.items()] +
                 [dict(l=l, slots=f"b/d shared with l = {other}", **v) for (l, other), v in common.items()]).to_csv(os.path.join(out, "beverloo_fit.csv"),
                                                                    index=False, float_format="%.6g")
    pd.set_option("display.width", 200)
    print(df[["l", "fill", "b_m", "b_over_d", "W_per_L_kg_s_m", "W_per_L_err_kg_s_m", "drift",
              "parcels_in_window", "discharged_fraction_at_end", "rho_b_kg_m3", "bed_height_m",
              "beverloo_fit_W_per_L_kg_s_m"]].to_string(index=False))
    for l, v in fits.items():
        print(f"l = {l}: C' = {v['C']:.3f} +- {v['C_err']:.3f}, k = {v['k']:.3f} +- {v['k_err']:.3f} "
              f"({v['n']} slots, rms relative misfit of W {v['rms_rel']:.3f})")
    for (l, other), v in common.items():
        print(f"l = {l} (range shared with l = {other}), b/d in [{v['b_over_d_min']:.1f}, {v['b_over_d_max']:.1f}]: C' = {v['C']:.3f} +- {v['C_err']:.3f}, "
              f"k = {v['k']:.3f} +- {v['k_err']:.3f} ({v['n']} slots, rms relative misfit of W {v['rms_rel']:.3f})")
    if ref_l:
        for r in df[df.l != ref_l].itertuples():
            law = getattr(r, "law_of_l%s_fit_W_per_L_kg_s_m" % ref_l)
            print(f"l = {r.l}, b = {r.b_m * 1e3:.3f} mm (b/d = {r.b_over_d:.1f}): W/L {r.W_per_L_kg_s_m:.4g} against the "
                  f"law of l = {ref_l}'s C', k with d = {r.d_m * 1e6:.0f} um: {law:.4g} ({r.W_per_L_kg_s_m / law - 1:+.3f})")
    # Fill height: the half fill against the full one at the same slot.
    for l in ratios:
        h = df[(df.l == l) & (df.fill == "half")]
        for r in h.itertuples():
            full = df[(df.l == l) & (df.fill == "full") & np.isclose(df.b_m, r.b_m)]
            if len(full):
                f = full.iloc[0]
                print(f"fill height, l = {l}, b = {r.b_m * 1e3:.3f} mm: bed {f.bed_height_m * 1e3:.1f} mm -> "
                      f"{r.bed_height_m * 1e3:.1f} mm, W/L {f.W_per_L_kg_s_m:.4g} -> {r.W_per_L_kg_s_m:.4g} kg/s/m "
                      f"({r.W_per_L_kg_s_m / f.W_per_L_kg_s_m - 1:+.3f})")
    # Coarse against finer at the same slot width.
    ls = sorted(set(df.l))
    for coarse in ls[::-1]:
        for fine in [x for x in ls if x < coarse]:
            agree = []
            for r in df[(df.l == coarse) & (df.fill == "full")].itertuples():
                f = df[(df.l == fine) & (df.fill == "full") & np.isclose(df.b_m, r.b_m)]
                if len(f):
                    rel = r.W_per_L_kg_s_m / f.iloc[0].W_per_L_kg_s_m - 1
                    agree.append((r.b_over_d, rel))
                    print(f"l = {coarse} vs l = {fine}, b = {r.b_m * 1e3:.3f} mm (b/d = {r.b_over_d:.1f}): {rel:+.3f}")
            ok = [bd for bd, rel in agree if all(abs(x) <= AGREE for y, x in agree if y >= bd)]
            if agree:
                print(f"l = {coarse} vs l = {fine}: within {AGREE:.0%} from b/d_parcel = "
                      f"{min(ok) if ok else 'none of the slots run'}")
    plot(out, df, fits, series)
    return df, fits


def plot(out, df, fits, series):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.4))
    colours = {3: "C0", 2: "C1", 1: "C2"}
    for (l, b_mm, tag), (t, M) in series.items():
        if l == max(fits or [3]) or tag:
            r = df[(df.l == l) & np.isclose(df.b_m, b_mm * 1e-3) & (df.fill == ("half" if tag else "full"))].iloc[0]
            ax[0].plot(t, M / r.L_m, ls="--" if tag else "-",
                       label=f"l={l}, b={b_mm} mm" + (" (half fill)" if tag else ""))
    ax[0].axvspan(*WINDOW, color="0.9", zorder=0, label="steady window")
    ax[0].set(xlabel="t [s]", ylabel="discharged mass per slot length M/L [kg/m]",
              title="mass below the floor (energy.csv `removed`)")
    ax[0].legend(fontsize=7)
    bb = np.linspace(0, df.b_m.max() * 1.05, 200)
    for l in sorted(set(df.l)):
        r = df[(df.l == l) & (df.fill == "full")]
        ax[1].errorbar(r.b_m * 1e3, r.W_per_L_kg_s_m ** (2 / 3),
                       yerr=(2 / 3) * r.W_per_L_kg_s_m ** (-1 / 3) * r.W_per_L_err_kg_s_m, fmt="o",
                       color=colours.get(l), label=f"l = {l} (d = {l * D_O * 1e6:.0f} um)")
        if l in fits:
            v = fits[l]
            ax[1].plot(bb * 1e3, np.maximum(v["a"] + v["s"] * bb, 0), color=colours.get(l),
                       label=f"fit: C' = {v['C']:.2f}+-{v['C_err']:.2f}, k = {v['k']:.2f}+-{v['k_err']:.2f}")
        elif fits:
            ref = fits[max(fits)]
            rho_b, d = r.rho_b_kg_m3.iloc[0], r.d_m.iloc[0]
            y = (ref["C"] * rho_b * math.sqrt(G)) ** (2 / 3) * np.maximum(bb - ref["k"] * d, 0)
            ax[1].plot(bb * 1e3, y, ls="--", color=colours.get(l),
                       label=f"law of l = {max(fits)}'s C', k with d = {d * 1e6:.0f} um")
    h = df[df.fill == "half"]
    ax[1].plot(h.b_m * 1e3, h.W_per_L_kg_s_m ** (2 / 3), "kx", label="half fill")
    for l in sorted(set(df.l)):
        r = df[(df.l == l) & (df.fill == "full")]
        scale = r.rho_b_kg_m3 * math.sqrt(G) * r.d_m ** 1.5
        ax[2].errorbar(r.b_over_d, (r.W_per_L_kg_s_m / scale) ** (2 / 3),
                       yerr=(2 / 3) * (r.W_per_L_kg_s_m / scale) ** (-1 / 3) * r.W_per_L_err_kg_s_m / scale,
                       fmt="o", color=colours.get(l), label=f"l = {l}")
    if fits:
        ref = fits[max(fits)]
        xx = np.linspace(0, df.b_over_d.max() * 1.05, 200)
        ax[2].plot(xx, ref["C"] ** (2 / 3) * np.maximum(xx - ref["k"], 0), color="0.4",
                   label=f"law of l = {max(fits)}'s fit")
    ax[2].set(xlabel="b / d_parcel", ylabel="(W / (L rho_b g^0.5 d^1.5))^(2/3)",
              title="in parcel units: C'^(2/3) (b/d - k)")
    ax[2].set_xlim(left=0)
    ax[2].set_ylim(bottom=0)
    ax[2].legend(fontsize=7)
    ax[1].set(xlabel="slot width b [mm]", ylabel="(W/L)^(2/3) [(kg/s/m)^(2/3)]",
              title="Beverloo: (W/L)^(2/3) = (C' rho_b g^0.5)^(2/3) (b - k d)")
    ax[1].set_xlim(left=0)
    ax[1].set_ylim(bottom=0)
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "beverloo.png"), dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--cgdem", default="build/cgdem")
    p.add_argument("--out", default="out/beverloo")
    p.add_argument("--ratios", default="3,2")
    p.add_argument("--slots", default=",".join(str(x) for x in SLOTS_MM), help="slot widths b [mm] to run")
    p.add_argument("--analyse-only", action="store_true")
    a = p.parse_args()
    ratios = [int(x) for x in a.ratios.split(",")]
    if not a.analyse_only:
        run_all(a.cgdem, a.out, ratios, [float(x) for x in a.slots.split(",")])
    analyse(a.out, ratios)


if __name__ == "__main__":
    main()
