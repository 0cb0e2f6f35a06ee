#!/usr/bin/env python3
"""Discharge of the Beverloo bin through a slot in vacuum and in air (issue #17, item 2).

The bin, the powder and the slots are those of ../beverloo_discharge/ (bin_l<l>.toml, whose
[air] section is switched on here with --set air.enabled=true). For each system:
  fill          t = -0.10..0 s in vacuum, slot closed; settled.bin
  vacuum        --restart fill/settled.bin, slot open, t = 0..0.08 s
  open          the same with air (--set air.enabled=true: the air starts at rest around the
                settled bed), top and outlet open to the room (gauge pressure 0)
  sealed        the same with air and the top sealed (air.boundary.z_max = "wall"): the
                volume of powder that leaves must be replaced by air entering through the slot
Systems: l = 3 (the paper's coarse-grained parcels, 375 um standing for 125 um), l = 2, the
original particles (l1: 125 um, in bin_l1_air.toml beside this script, a 1 mm slab), and the
simply-large particles (l = 1, d_O = 375 um: the parcels' size without the scaling).

The rate W is the slope of the discharged mass over the window, as in the Beverloo sweep
(run_sweep.rate_of). From the air snapshots (every 2 ms) the gauge pressure (the still air's
removed) averaged over the window, in the slot's column (the cells whose centres lie within
the slot's width), against height; the outlet's gradient G = dp/dz is that profile's slope at
`--arch` x b above the floor's top (default b/2: the top of the free-fall arch over the slot).
The mean gradient over the height b above the floor is reported beside it, to show how much
the comparison depends on where G is read.

Reference: Crewdson, Ormond & Nedderman (1977), Powder Technol. 16, 197-207: the air's
pressure gradient at the outlet acts as a change of gravity, g -> g + (1/rho_b) dp/dz
(z upward; dp/dz < 0 when the air pushes up against the flow), so with Beverloo's W ~ g^(1/2)
    W_air / W_vacuum = (1 + G / (rho_b g))^(1/2).
The prediction uses the run's own G and rho_b; the table gives it beside the measured ratio.

Usage (from the repository root; one thread per run, runs one after another):
    /usr/bin/python3 validation/discharge_air/run_air.py [--systems l3,l2,large] [--slots 2.25,3.0,3.75]
    /usr/bin/python3 validation/discharge_air/run_air.py --analyse-only
Writes OUT/discharge_air_table.csv, OUT/pressure_profiles.csv and OUT/discharge_air.png.
"""
import argparse
import glob
import math
import os
import sys

import h5py
import numpy as np
import pandas as pd

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "beverloo_discharge"))
import run_sweep as sweep  # noqa: E402

G_ACC = 9.81
# system -> (case ratio or case file, extra --set arguments)
def parcels_of_375um(d_o_um, dt=None):
    """The l = 3 bin's parcels (375 um) standing for particles of d_O: ratio 375 / d_O. The
    collision time is the original particles' (it goes as d_O^(3/2)): below 125 um the DEM
    step `dt` [s] must shrink with it."""
    return (3, ["--set", f"particles.species[0].d_original={d_o_um}e-6",
                "--set", f"particles.species[0].ratio={375.0 / d_o_um:.10g}"] +
            (["--set", f"time.dt={dt}"] if dt else []))


SYSTEMS = {
    # The original particles (125 um, l = 1) in a 1 mm slab with the bin's air: bin_l1_air.toml
    # beside this script (the sweep's 0.5 mm slab is one air cell thick). Its rate per unit
    # slot length compares with the other systems'.
    "l1": (os.path.join(HERE, "bin_l1_air.toml"), []),
    "l3": (3, []),
    "l2": (2, []),
    "large": parcels_of_375um(375),
    # The size sweep: the same 375 um parcels (the same bin, parcel count and mass) standing
    # for particles of 50 .. 375 um. What differs with d_O is the drag (it takes d_O) and the
    # contact stiffness l^3 k, which keeps the originals' collision time (3.1 us at 50 um,
    # 5.7 us at 75 um: 10 steps need dt <= 3.1e-7 / 5.7e-7 s). "l3" is d_O = 125 um,
    # "large" 375 um.
    "d050": parcels_of_375um(50, 2.5e-7),
    "d075": parcels_of_375um(75, 5e-7),
    "d188": parcels_of_375um(187.5),
    "d250": parcels_of_375um(250),
    # The original particles of 250 um (l = 1) in the l = 2 bin (250 um, a 1 mm slab, two air
    # cells across): the l = 1 point of the size curve at 250 um, against "d250" (the 375 um
    # parcels, l = 1.5) and "large" (the 375 um particles unscaled, its simply large particles).
    "o250": (2, ["--set", "particles.species[0].d_original=250e-6", "--set", "particles.species[0].ratio=1"]),
    # The original particles of 187.5 um (l = 1, 27,800 in the same 1 mm slab), against "d188"
    # (the 375 um parcels, l = 2).
    "o188": (2, ["--set", "particles.species[0].d_original=187.5e-6", "--set", "particles.species[0].ratio=1"]),
}
MODES = {
    "vacuum": ["--set", "air.enabled=false"],
    "open": ["--set", "air.enabled=true"],
    "sealed": ["--set", "air.enabled=true", "--set", "air.boundary.z_max=\"wall\""],
}
SNAP = 2e-3  # s, snapshot interval of the discharges (air fields for the pressure profile)


def fill_dir(out, system):
    return os.path.join(out, f"fill_{system}")


def run_dir(out, system, b, mode):
    return os.path.join(out, f"{system}_b{b * 1e3:.3f}mm_{mode}")


def run_all(cgdem, out, systems, slots, modes):
    os.makedirs(out, exist_ok=True)
    for system in systems:
        l, extra = SYSTEMS[system]
        case = l if isinstance(l, str) else sweep.case_of(l)
        f = fill_dir(out, system)
        sweep.run(cgdem, [case, "--set", "time.end=0.0", "--set", "air.enabled=false", *sweep.slot_sets(0.0), *extra],
                  f, f + ".log")
        for b_mm in slots[system]:
            b = b_mm * 1e-3
            for mode in modes:
                d = run_dir(out, system, b, mode)
                sweep.run(cgdem, [case, "--restart", os.path.join(f, "settled.bin"), "--set", f"time.end={sweep.T_END}",
                                  "--set", f"output.snapshot_interval={SNAP}", *sweep.slot_sets(b), *extra,
                                  *MODES[mode]], d, d + ".log")


def pressure_profile(run, b):
    """Window-mean gauge pressure [Pa] in the slot's column against the cell-centre height z [m]."""
    cfg = sweep.resolved(run)
    rho = cfg["air"]["density"]
    H = cfg["domain"]["max"][2] - cfg["domain"]["min"][2]
    p_open = cfg["air"].get("boundary", {}).get("open_pressure", 0.0)
    acc, n = None, 0
    for path in sorted(glob.glob(os.path.join(run, "air_*.h5"))):
        with h5py.File(path) as h:
            t = float(h.attrs["time"])  # s (attribute time_units)
            if not (sweep.WINDOW[0] - 1e-9 <= t <= sweep.WINDOW[1] + 1e-9):
                continue
            nx, ny, nz = h["grid/n"][:]
            o, dx = h["grid/origin"][:], h["grid/spacing"][:]
            p = h["cells/p"][:]
        xc = o[0] + (np.arange(nx) + 0.5) * dx[0]
        z = o[2] + (np.arange(nz) + 0.5) * dx[2]
        cols = np.abs(xc - sweep.X_C) < b / 2
        gauge = p[:, :, cols].mean(axis=(1, 2)) - (p_open + rho * G_ACC * (H - z))
        acc = gauge if acc is None else acc + gauge
        n += 1
    if n == 0:
        return None, None, 0
    return z, acc / n, n


def gradient_at(z, p, zc):
    """dp/dz [Pa/m] of the profile at height zc (central differences, linear in between)."""
    return float(np.interp(zc, z, np.gradient(p, z)))


def outlet_gradient(z, p, b, arch):
    """The outlet's gradient G: dp/dz at `arch` x b above the floor's top (default b/2: the
    top of a free-fall arch of radius b/2 spanning the slot, the nearest point of the bed to
    the outlet in Crewdson's radial picture)."""
    return gradient_at(z, p, sweep.FLOOR_TOP + arch * b)


def arch_mean_gradient(z, p, b):
    """The mean gradient over the slot's width above it: (p(z_f + b) - p(z_f)) / b."""
    zf = sweep.FLOOR_TOP
    return float((np.interp(zf + b, z, p) - np.interp(zf, z, p)) / b)


def analyse(out, systems, slots, arch):
    rows, profiles = [], []
    for system in systems:
        for b_mm in slots[system]:
            b = b_mm * 1e-3
            base = None
            for mode in MODES:
                d = run_dir(out, system, b, mode)
                if not os.path.exists(os.path.join(d, "metrics.csv")):
                    continue
                rho_b, phi, top = sweep.bulk_density(fill_dir(out, system))
                r = sweep.rate_of(d)
                r.pop("t"), r.pop("M")
                sp = sweep.resolved(d)["particles"]["species"][0]
                row = dict(system=system, mode=mode, ratio=sp["ratio"], d_O_m=sp["d_original"], b_m=b,
                           b_over_d=b / r["d_m"], rho_b_kg_m3=rho_b, phi=phi,
                           bed_height_m=top + r["d_m"] / 2 - sweep.FLOOR_TOP, **r)
                if mode == "vacuum":
                    base = row["W_per_L_kg_s_m"]
                z, p, n = pressure_profile(d, b) if mode != "vacuum" else (None, None, 0)
                if p is not None:
                    Gz = outlet_gradient(z, p, b, arch)
                    Gm = arch_mean_gradient(z, p, b)
                    row.update(air_snapshots=n, p_arch_top_Pa=float(np.interp(sweep.FLOOR_TOP + arch * b, z, p)),
                               p_bed_top_Pa=float(np.interp(top, z, p)), dpdz_outlet_Pa_m=Gz,
                               crewdson_ratio=math.sqrt(max(1 + Gz / (rho_b * G_ACC), 0.0)),
                               dpdz_mean_over_b_Pa_m=Gm,
                               crewdson_ratio_mean_over_b=math.sqrt(max(1 + Gm / (rho_b * G_ACC), 0.0)))
                    for zi, pi in zip(z, p):
                        profiles.append(dict(system=system, mode=mode, b_m=b, z_m=zi, p_gauge_Pa=pi))
                rows.append(row)
            for row in rows:
                if row["system"] == system and math.isclose(row["b_m"], b) and base:
                    row["W_over_vacuum"] = row["W_per_L_kg_s_m"] / base
    df = pd.DataFrame(rows)
    if df.empty:
        sys.exit(f"no finished runs in {out}")
    df.to_csv(os.path.join(out, "discharge_air_table.csv"), index=False, float_format="%.6g")
    pd.DataFrame(profiles).to_csv(os.path.join(out, "pressure_profiles.csv"), index=False, float_format="%.6g")
    write_markdown(out, df)
    pd.set_option("display.width", 220)
    cols = [c for c in ["system", "mode", "b_m", "b_over_d", "W_per_L_kg_s_m", "W_per_L_err_kg_s_m", "drift",
                        "W_over_vacuum", "dpdz_outlet_Pa_m", "crewdson_ratio", "crewdson_ratio_mean_over_b", "p_bed_top_Pa",
                        "rho_b_kg_m3"] if c in df]
    print(df[cols].to_string(index=False))
    plot(out, df, pd.DataFrame(profiles))
    return df


def write_markdown(out, df):
    """discharge_air_table.md: the table of the README, one row per system and slot."""
    lines = ["| system | d_O [um] | l | b [mm] | b / d | W/L vacuum [kg/s/m] | W/L top open | W/L top sealed | "
             "open / vacuum | form, open | sealed / vacuum | form, sealed | G open / sealed [Pa/m] | "
             "headspace, sealed [Pa] |", "|" + "---|" * 14]
    for (system, b), g in df.groupby(["system", "b_m"], sort=False):
        m = {r["mode"]: r for _, r in g.iterrows()}
        if "vacuum" not in m:
            continue
        v, o, s = m["vacuum"], m.get("open"), m.get("sealed")

        def w(r):
            return f"{r['W_per_L_kg_s_m']:.4f} +- {r['W_per_L_err_kg_s_m']:.4f}" if r is not None else ""

        def f(r, key, fmt="{:.3f}"):
            return fmt.format(r[key]) if r is not None and key in r and r[key] == r[key] else ""

        lines.append(f"| {system} | {v['d_O_m'] * 1e6:.4g} | {v['ratio']:.4g} | {b * 1e3:.3g} | {v['b_over_d']:.1f} | "
                     f"{w(v)} | {w(o)} | {w(s)} | {f(o, 'W_over_vacuum')} | {f(o, 'crewdson_ratio')} | "
                     f"{f(s, 'W_over_vacuum')} | {f(s, 'crewdson_ratio')} | {f(o, 'dpdz_outlet_Pa_m', '{:.0f}')} / "
                     f"{f(s, 'dpdz_outlet_Pa_m', '{:.0f}')} | {f(s, 'p_bed_top_Pa', '{:.1f}')} |")
    with open(os.path.join(out, "discharge_air_table.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


def plot(out, df, prof):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(18, 4.4))
    marks = {"l3": "o", "l2": "s", "large": "^", "l1": "D"}
    for mode, c in [("open", "C0"), ("sealed", "C3")]:
        s = df[df["mode"] == mode]
        if "crewdson_ratio" in s:
            for system, g in s.groupby("system"):
                ax[0].plot(g["crewdson_ratio"], g["W_over_vacuum"], marks.get(system, "o"), color=c,
                           label=f"{system}, top {mode}")
    ax[0].plot([0, 1.05], [0, 1.05], "k--", lw=0.8, label="Crewdson et al. 1977")
    ax[0].set(xlabel="(1 + G / (rho_b g))^(1/2), G = dp/dz at the outlet (measured)", ylabel="W_air / W_vacuum",
              title="air-impeded discharge: measured against the effective-gravity form", xlim=(0, 1.05), ylim=(0, 1.05))
    ax[0].legend(fontsize=7)
    if not prof.empty:
        for (system, mode, b), g in prof.groupby(["system", "mode", "b_m"]):
            ax[1].plot(g["p_gauge_Pa"], g["z_m"] * 1e3, ls="-" if mode == "sealed" else ":",
                       label=f"{system}, b = {b * 1e3:.2f} mm, top {mode}")
    ax[1].axhline(sweep.FLOOR_TOP * 1e3, color="0.5", lw=0.8)
    ax[1].set(xlabel="gauge pressure in the slot's column, window mean [Pa]", ylabel="z [mm]",
              title="air pressure above the slot")
    ax[1].legend(fontsize=6)
    # The size sweep: the same 375 um parcels standing for particles of d_O (b = 2.25 mm).
    sw = df[np.isclose(df["b_m"], 2.25e-3) & (df["d_m"] > 0.37e-3) & (df["d_m"] < 0.38e-3)].copy()
    sw["d_O_um"] = sw["d_O_m"] * 1e6
    for mode, c in [("vacuum", "k"), ("open", "C0"), ("sealed", "C3")]:
        g = sw[sw["mode"] == mode].sort_values("d_O_um")
        if len(g):
            ax[2].errorbar(g["d_O_um"], g["W_per_L_kg_s_m"] / (g["rho_b_kg_m3"] * math.sqrt(G_ACC) * g["b_m"] ** 1.5),
                           yerr=g["W_per_L_err_kg_s_m"] / (g["rho_b_kg_m3"] * math.sqrt(G_ACC) * g["b_m"] ** 1.5),
                           fmt="o-", color=c, label=mode if mode == "vacuum" else f"air, top {mode}")
    # The finer parcels of the same 125 um powder (l = 2: 250 um, l = 1: the particles
    # themselves) and the original 250 and 187.5 um particles (o250, o188), open markers: where they sit
    # against the 375 um parcels' points.
    fine = df[np.isclose(df["b_m"], 2.25e-3) & (df["d_m"] < 0.37e-3)]
    for (system, mode), g in fine.groupby(["system", "mode"]):
        c = {"vacuum": "k", "open": "C0", "sealed": "C3"}[mode]
        y = g["W_per_L_kg_s_m"] / (g["rho_b_kg_m3"] * math.sqrt(G_ACC) * g["b_m"] ** 1.5)
        ax[2].plot(g["d_O_m"] * 1e6, y, {"l1": "D", "l2": "s", "o250": "D", "o188": "D"}.get(system, "v"), mfc="none", color=c, ms=8,
                   label=f"{system} (parcels of {g['d_m'].iloc[0] * 1e6:.0f} um), {mode}")
    ax[2].set(xscale="log", xlabel="particle diameter d_O [um] (parcels of 375 um, l = 375 um / d_O)",
              ylabel="W / (L rho_b g^0.5 b^1.5)", title="dimensionless rate against particle size, b = 2.25 mm")
    ax[2].set_ylim(bottom=0)
    ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "discharge_air.png"), dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--cgdem", default="build/cgdem")
    p.add_argument("--out", default="out/discharge_air")
    p.add_argument("--systems", default="l3,l2,large", help="l1 (the original particles), l3, l2, large, d050, "
                   "d075, d188, d250, o250, o188")
    p.add_argument("--slots", default="2.25,3.0,3.75", help="slot widths b [mm] at l = 3; 2.25 for the others")
    p.add_argument("--modes", default="vacuum,open,sealed")
    p.add_argument("--arch", type=float, default=0.5,
                   help="height above the floor's top, in slot widths, at which the outlet's gradient is read")
    p.add_argument("--analyse-only", action="store_true")
    a = p.parse_args()
    systems = a.systems.split(",")
    l3_slots = [float(x) for x in a.slots.split(",")]
    slots = {s: (l3_slots if s == "l3" else [2.25]) for s in systems}
    if not a.analyse_only:
        run_all(a.cgdem, a.out, systems, slots, a.modes.split(","))
    analyse(a.out, systems, slots, a.arch)


if __name__ == "__main__":
    main()
