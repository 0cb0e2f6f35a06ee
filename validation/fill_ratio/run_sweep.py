#!/usr/bin/env python3
"""Fill ratio against shoe speed, in vacuum and with air (issue #17, item 3).

Case: shoe_slab.toml beside this script (the paper's shoe over a simple die 10 mm long and
7 mm deep, a 2.4 mm slab periodic in y, l = 3). For each ratio l:
  settle      t = -0.15 .. 0 s in vacuum, the shoe at rest: settled.bin
  vacuum_v    --restart settle/settled.bin, shoe speed v, in vacuum
  air_v       the same with air (the air starts at rest around the settled bed)
Each pass ends when the shoe's rear wall lies centred over the die's mouth:
t_end = (travel + (shoe_wall - mouth_length) / 2) / v + ramp, where travel = mouth_x0 +
mouth_length - cavity_x0 is the distance after which the cavity's rear inner wall has passed
the die's far edge (25 mm in shoe_slab.toml) and ramp is the shoe's start-up time. From then
on the die is closed and its powder can no longer change.

and once per ratio
  full        the die filled at rest: the same pour with the cavity standing over the die
              (cavity and pouring column shifted by mouth_x0 - cavity_x0, shoe speed 0), in
              vacuum; its mass in the die at t = 0 is M_full, a completely filled die.

Fill ratio (Wu, Dihoru & Cocks 2003, Powder Technol. 134, 24-39):
    delta = M_die / M_full
with M_die the mass in the die at the end of a pass (diagnostics.csv, parcels whose centres
lie below the table top inside the die). Beside it delta_b = M_die / (rho_b V_die), with
V_die the die's volume and rho_b the settled shoe bed's bulk density (parcels whose centres
lie 1 mm from the cavity's walls and from the bed's floor and surface, at t = 0): it counts
the looser packing along the die's walls as missing powder. Above a critical speed v_c,
    delta = (v_c / v)^n,
fitted by least squares on log delta = n log v_c - n log v over the speeds with
delta < DELTA_FULL (the die visibly not full); the uncertainty of n and v_c is the fit's
standard error (first-order propagation for v_c).

Usage (from the repository root; one thread per run, --jobs runs side by side):
    /usr/bin/python3 validation/fill_ratio/run_sweep.py [--speeds 0.5,0.3,...] [--ratios 3,2] [--jobs 2]
    /usr/bin/python3 validation/fill_ratio/run_sweep.py --systems 250:1.5,375:1 [--modes air] ...
    /usr/bin/python3 validation/fill_ratio/run_sweep.py --analyse-only
Writes OUT/fill_ratio_table.csv, OUT/fill_ratio_fit.csv, OUT/fill_ratio_table.md and
OUT/fill_ratio.png.
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
CASE = os.path.join(HERE, "shoe_slab.toml")
SPEEDS = [0.5, 0.3, 0.2, 0.1, 0.05, 0.02]  # m/s, the shoe's speed (fastest, cheapest first)
DELTA_FULL = 0.95     # delta below this: the die is not full, the point enters the fit
MODES = {"vacuum": ["--set", "air.enabled=false"], "air": []}


def case_config(case):
    with open(case, "rb") as f:
        return tomllib.load(f)


def t_end(case, v):
    """The time the shoe's rear wall lies centred over the die's mouth (the die closed)."""
    w = case_config(case)["walls"]["die_filling"]
    travel = w["mouth_x0"] + w["mouth_length"] - w["cavity_x0"]
    return (travel + 0.5 * (w["shoe_wall"] - w["mouth_length"])) / v + w.get("shoe_ramp", 1e-3)


D_REF = 125.0   # um, the paper's particle: systems of this size keep the folder names "l3", "l2"


def tag(sysm):
    """Folder tag of a system (d_O in um, ratio l): "l3" for the paper's 125 um, "d250_l1.5" otherwise."""
    d, l = sysm
    return f"l{l:g}" if d == D_REF else f"d{d:g}_l{l:g}"


def settle_dir(out, sysm):
    return os.path.join(out, f"settle_{tag(sysm)}")


def full_dir(out, sysm):
    return os.path.join(out, f"full_{tag(sysm)}")


def full_sets(case):
    """--set arguments of the die filled at rest: the cavity and the pouring column over the die."""
    c = case_config(case)
    w = c["walls"]["die_filling"]
    shift = w["mouth_x0"] - w["cavity_x0"]
    ins = c["particles"]["insert"][0]
    lo, hi = list(ins["min"]), list(ins["max"])
    lo[0] += shift
    hi[0] += shift
    fmt = lambda v: "[" + ",".join(f"{x:.9g}" for x in v) + "]"
    return ["--set", f"walls.die_filling.cavity_x0={w['mouth_x0']:.9g}", "--set", "walls.die_filling.shoe_speed=0",
            "--set", f"particles.insert[0].min={fmt(lo)}", "--set", f"particles.insert[0].max={fmt(hi)}"]


def run_dir(out, sysm, mode, v):
    return os.path.join(out, f"{tag(sysm)}_{mode}_v{v:g}")


def system_sets(sysm):
    """--set arguments of a system: the original diameter and the ratio where they differ from the case's."""
    sp = case_config(CASE)["particles"]["species"][0]
    d, l = sysm
    out = []
    if abs(d * 1e-6 - sp["d_original"]) > 1e-12:
        out += ["--set", f"particles.species[0].d_original={d * 1e-6:.9g}"]
    if l != sp.get("ratio", 1.0):
        out += ["--set", f"particles.species[0].ratio={l:g}"]
    return out


def command(cgdem, args, out):
    return [cgdem, "run", CASE, *args, "--threads", "1", "--output", out]


MACHINE_JOBS = None   # --machine-jobs: at most this many cgdem processes on the machine, ours or not


def machine_busy(running):
    if MACHINE_JOBS is None:
        return False
    n = subprocess.run(["pgrep", "-c", "cgdem"], capture_output=True, text=True).stdout.strip()
    return int(n or 0) >= MACHINE_JOBS


def run_batch(jobs, todo):
    """Runs the (command, out) pairs, `jobs` at a time; stops at the first failure."""
    running, pending = [], []
    for cmd, out in todo:
        if os.path.exists(os.path.join(out, "metrics.csv")):
            print(f"  {out}: done before, kept")
        else:
            pending.append((cmd, out))
    todo = pending
    while todo or running:
        while todo and len(running) < jobs and not machine_busy(running):
            cmd, out = todo.pop(0)
            log = open(out + ".log", "w")
            p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env={**os.environ, "OMP_NUM_THREADS": "1"})
            running.append((p, cmd, out, time.time(), log))
        time.sleep(2)
        for item in list(running):
            p, cmd, out, t0, log = item
            if p.poll() is None:
                continue
            running.remove(item)
            log.close()
            if p.returncode != 0:
                for q in running:
                    q[0].terminate()
                sys.exit(f"run failed ({p.returncode}): {' '.join(cmd)}; see {out}.log")
            print(f"  {out}: {time.time() - t0:.0f} s wall", flush=True)


def run_all(cgdem, out, systems, speeds, modes, jobs):
    os.makedirs(out, exist_ok=True)
    for l in systems:
        s = settle_dir(out, l)
        f = full_dir(out, l)
        still = ["--set", "time.end=0.0", "--set", "air.enabled=false", *system_sets(l)]
        run_batch(jobs, [(command(cgdem, still, s), s), (command(cgdem, [*still, *full_sets(CASE)], f), f)])
        settled = os.path.join(s, "settled.bin")
        runs = [(command(cgdem, ["--restart", settled, "--set", f"walls.die_filling.shoe_speed={v:g}",
                                 "--set", f"time.end={t_end(CASE, v):.6g}", *system_sets(l), *MODES[m]],
                         run_dir(out, l, m, v)), run_dir(out, l, m, v))
                for v in speeds for m in modes]
        run_batch(jobs, runs)


def resolved(d):
    with open(os.path.join(d, "config.resolved.toml"), "rb") as f:
        return tomllib.load(f)


def geometry(cfg):
    w = cfg["walls"]["die_filling"]
    lo, hi = cfg["domain"]["min"], cfg["domain"]["max"]
    return dict(table=w["table_top"], mouth_x0=w["mouth_x0"], mouth_len=w["mouth_length"], depth=w["deep_depth"],
                width=hi[1] - lo[1], cav_x0=w["cavity_x0"], cav_len=w["cavity_size"][0])


def last_snapshot(d):
    return sorted(glob.glob(os.path.join(d, "particles_*.h5")))[-1]


def interior_packing(snap, x0, x1, z0, margin=1e-3):
    """Solid fraction of the parcels whose centres lie `margin` inside [x0, x1] and between
    z0 + margin and the bed's surface (99th percentile of the heights in [x0, x1]) - margin."""
    with h5py.File(snap) as h:
        x = h["particles/x"][:]
        d = h["particles/d"][:]
    inx = (x[:, 0] > x0) & (x[:, 0] < x1)
    top = np.percentile(x[inx, 2], 99)
    lo, hi = z0 + margin, top - margin
    sel = inx & (x[:, 0] > x0 + margin) & (x[:, 0] < x1 - margin) & (x[:, 2] > lo) & (x[:, 2] < hi)
    return np.sum(np.pi / 6 * d[sel] ** 3), (x1 - x0 - 2 * margin) * (hi - lo), top


def bulk_density(settle):
    cfg = resolved(settle)
    g = geometry(cfg)
    rho_p = cfg["particles"]["species"][0]["density"]
    vs, area, top = interior_packing(last_snapshot(settle), g["cav_x0"], g["cav_x0"] + g["cav_len"], g["table"])
    phi = vs / (area * g["width"])
    return phi * rho_p, phi, top - g["table"]


def final_state(d):
    diag = pd.read_csv(os.path.join(d, "diagnostics.csv"), comment="#")
    met = pd.read_csv(os.path.join(d, "metrics.csv"), comment="#")
    last = diag.iloc[-1]
    return dict(t_end_s=float(last["t_s"]), M_die_kg=float(last["mass_in_die_kg"]),
                M_shoe_kg=float(last["mass_in_shoe_kg"]), rate_max_kg_s=float(diag["transfer_rate_kg_s"].max()),
                p_floor_max_Pa=float(diag["p_floor_Pa"].max()) if "p_floor_Pa" in diag else math.nan,
                wall_s=wall_seconds(d + ".log"), **{k: float(met[k].iloc[0]) for k in ["front_time_s"] if k in met})


def wall_seconds(log):
    try:
        for line in open(log):
            if line.startswith("wall "):
                return float(line.split()[1])
    except OSError:
        pass
    return math.nan


def fit(rows):
    """n and v_c of delta = (v_c / v)^n from the rows with delta < DELTA_FULL."""
    pts = [(r["v_m_s"], r["delta"]) for r in rows if 0 < r["delta"] < DELTA_FULL]
    if len(pts) < 2:
        return dict(points=len(pts))
    lv = np.log([p[0] for p in pts])
    ld = np.log([p[1] for p in pts])
    A = np.vstack([np.ones_like(lv), lv]).T
    coef, res, *_ = np.linalg.lstsq(A, ld, rcond=None)
    a, s = coef                      # log delta = a + s log v, s = -n, a = n log v_c
    n = -s
    dof = len(pts) - 2
    if dof > 0:
        sigma2 = float(np.sum((ld - A @ coef) ** 2)) / dof
        cov = sigma2 * np.linalg.inv(A.T @ A)
    else:
        cov = np.full((2, 2), np.nan)
    vc = math.exp(a / n)
    # v_c = exp(a / n) = exp(-a / s): d vc / da = -vc / s, d vc / ds = vc a / s^2
    J = np.array([-vc / s, vc * a / s ** 2])
    return dict(points=len(pts), n=n, n_err=math.sqrt(cov[1, 1]) if dof > 0 else math.nan, v_c_m_s=vc,
                v_c_err_m_s=math.sqrt(float(J @ cov @ J)) if dof > 0 else math.nan,
                v_min_fitted=min(p[0] for p in pts))


def analyse(out, systems, speeds):
    rows, fits = [], []
    for sysm in systems:
        d_um, l = sysm
        s = settle_dir(out, sysm)
        if not os.path.exists(os.path.join(s, "settled.bin")):
            continue
        rho_b, phi, bed = bulk_density(s)
        fd = os.path.join(full_dir(out, sysm), "diagnostics.csv")
        m_full = float(pd.read_csv(fd, comment="#")["mass_in_die_kg"].iloc[-1]) if os.path.exists(fd) else math.nan
        for m in MODES:
            mrows = []
            for v in speeds:
                d = run_dir(out, sysm, m, v)
                if not os.path.exists(os.path.join(d, "metrics.csv")):
                    continue
                g = geometry(resolved(d))
                V = g["mouth_len"] * g["width"] * g["depth"]
                st = final_state(d)
                r = dict(d_O_um=d_um, l=l, mode=m, v_m_s=v, rho_b_kg_m3=rho_b, phi_shoe=phi, bed_height_m=bed, V_die_m3=V,
                         M_full_kg=m_full, **st, delta=st["M_die_kg"] / m_full, delta_b=st["M_die_kg"] / (rho_b * V))
                mrows.append(r)
            rows += mrows
            if mrows:
                fits.append(dict(d_O_um=d_um, l=l, mode=m, **fit(mrows)))
    if not rows:
        sys.exit(f"no finished runs in {out}")
    df, ff = pd.DataFrame(rows), pd.DataFrame(fits)
    df.to_csv(os.path.join(out, "fill_ratio_table.csv"), index=False, float_format="%.6g")
    ff.to_csv(os.path.join(out, "fill_ratio_fit.csv"), index=False, float_format="%.6g")
    write_markdown(out, df, ff)
    pd.set_option("display.width", 200)
    print(df[["d_O_um", "l", "mode", "v_m_s", "M_die_kg", "M_full_kg", "M_shoe_kg", "delta", "delta_b", "p_floor_max_Pa",
              "wall_s"]].to_string(index=False))
    print(ff.to_string(index=False))
    plot(out, df, ff)
    return df, ff


def write_markdown(out, df, ff):
    with open(os.path.join(out, "fill_ratio_table.md"), "w") as f:
        f.write("| d_O um | l | v m/s | delta vacuum | delta air | air / vacuum | delta_b vacuum / air "
                "| die-floor p max, air Pa | powder left in the shoe, vacuum / air mg |\n")
        f.write("|---|---|---|---|---|---|---|---|---|\n")
        for (d, l, v), g in df.groupby(["d_O_um", "l", "v_m_s"], sort=True):
            vac = g[g["mode"] == "vacuum"]
            air = g[g["mode"] == "air"]
            get = lambda x, k, s=1.0: float(x[k].iloc[0]) * s if len(x) else math.nan
            dv, da = get(vac, "delta"), get(air, "delta")
            f.write(f"| {d:g} | {l:g} | {v:g} | {dv:.3f} | {da:.3f} | {da / dv if dv > 0 else math.nan:.3f} "
                    f"| {get(vac, 'delta_b'):.3f} / {get(air, 'delta_b'):.3f} | {get(air, 'p_floor_max_Pa'):.1f} "
                    f"| {get(vac, 'M_shoe_kg', 1e6):.1f} / {get(air, 'M_shoe_kg', 1e6):.1f} |\n")
        f.write("\n| d_O um | l | mode | points fitted | n | v_c m/s |\n|---|---|---|---|---|---|\n")
        for _, r in ff.iterrows():
            head = f"| {r['d_O_um']:g} | {r['l']:g} | {r['mode']} | {int(r['points'])} |"
            if r.get("points", 0) >= 2:
                f.write(f"{head} {r['n']:.2f} +- {r['n_err']:.2f} | {r['v_c_m_s']:.3f} +- {r['v_c_err_m_s']:.3f} |\n")
            else:
                f.write(f"{head} - | - |\n")


def plot(out, df, ff):
    """Left: the paper's 125 um powder at every ratio l (the coarse-graining check); right: the
    air's effect against the original particle size (one ratio per size)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sizes = sorted(df["d_O_um"].unique())
    two = len(sizes) > 1
    fig, axes = plt.subplots(1, 2 if two else 1, figsize=(11 if two else 6, 4.2), squeeze=False)
    mode_style = {"vacuum": ("o", "tab:blue"), "air": ("s", "tab:red")}
    size_colour = dict(zip(sizes, ["tab:green", "tab:red", "tab:purple", "tab:brown", "tab:orange"]))

    def curve(ax, g, fr, mk, c, ls, label, filled):
        ax.plot(g["v_m_s"], g["delta"], mk + ls, color=c, mfc=c if filled else "none", label=label)
        if len(fr) and fr["points"].iloc[0] >= 2:
            n, vc = fr["n"].iloc[0], fr["v_c_m_s"].iloc[0]
            vv = np.geomspace(vc, max(g["v_m_s"]), 50)
            ax.plot(vv, (vc / vv) ** n, "--", color=c, lw=0.8, label=f"  fit: v_c = {vc:.3f} m/s, n = {n:.2f}")

    ax = axes[0][0]
    ref = df[df["d_O_um"] == D_REF]
    lmax = ref["l"].max() if len(ref) else 3
    for (l, m), g in ref.groupby(["l", "mode"]):
        mk, c = mode_style[m]
        fr = ff[(ff["d_O_um"] == D_REF) & (ff["l"] == l) & (ff["mode"] == m)]
        curve(ax, g, fr, mk, c, "-" if l == lmax else ":", f"{m}, l = {l:g}", l == lmax)
    ax.set_title(f"d_O = {D_REF:g} um: ratio l (2.4 mm slab, 7 mm die)")
    if two:
        ax = axes[0][1]
        for (d, l, m), g in df[df["l"] == df.groupby("d_O_um")["l"].transform("max")].groupby(["d_O_um", "l", "mode"]):
            fr = ff[(ff["d_O_um"] == d) & (ff["l"] == l) & (ff["mode"] == m)]
            curve(ax, g, fr, "s" if m == "air" else "o", size_colour[d], "-" if m == "air" else ":",
                  f"{m}, d_O = {d:g} um (l = {l:g})", m == "air")
        ax.set_title("the air's effect against particle size")
    for ax in axes[0]:
        ax.axhline(1.0, color="0.6", lw=0.6)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("shoe speed v [m/s]")
        ax.set_ylabel("fill ratio delta = M_die / M_full [1]")
        ax.legend(fontsize=6.5)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fill_ratio.png"), dpi=130)


def main():
    global CASE, MACHINE_JOBS
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cgdem", default=os.path.join("build", "cgdem"))
    ap.add_argument("--out", default=os.path.join("out", "fill_ratio"))
    ap.add_argument("--ratios", default="3", help="ratios l of the case's powder (d_O = 125 um)")
    ap.add_argument("--systems", help="original diameter (um) and ratio pairs, e.g. 125:3,125:2,250:1.5,375:1 "
                    "(replaces --ratios)")
    ap.add_argument("--speeds", default=",".join(f"{v:g}" for v in SPEEDS))
    ap.add_argument("--modes", default="vacuum,air")
    ap.add_argument("--jobs", type=int, default=1, help="runs side by side (one thread each)")
    ap.add_argument("--machine-jobs", type=int, help="start a run only while fewer cgdem processes than this run "
                    "on the machine (other jobs included)")
    ap.add_argument("--case", default=CASE, help="the case file (default: shoe_slab.toml beside this script)")
    ap.add_argument("--analyse-only", action="store_true")
    a = ap.parse_args()
    CASE, MACHINE_JOBS = a.case, a.machine_jobs
    systems = ([tuple(float(y) for y in x.split(":")) for x in a.systems.split(",")] if a.systems
               else [(D_REF, float(x)) for x in a.ratios.split(",")])
    speeds = [float(x) for x in a.speeds.split(",")]
    if not a.analyse_only:
        run_all(a.cgdem, a.out, systems, speeds, a.modes.split(","), a.jobs)
    analyse(a.out, systems, speeds)


if __name__ == "__main__":
    main()
