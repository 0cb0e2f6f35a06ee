#!/usr/bin/env python3
"""The air's upward force on the powder over the slot, by height, from a run's snapshots.

For every particle and air snapshot of the steady window, the parcels whose centres lie over
the slot (|x - x_slot| < b/2) are binned by height (the air grid's cells); each gets the
force the run's model gives it, evaluated from the snapshot: the drag of the paper's law
(Ergun for eps <= 0.8, Wen-Yu above, with the original diameter d_O; coupling/drag.hpp)
with the air velocity and eps of its cell, plus the pressure-gradient force -V dp/dz. Per
bin: the upward air force per unit mass of the solids there, a_air [m/s^2], against g, and
the solid fraction. Where the bed is packed, a_air = -(1/rho_b) dp/dz is Crewdson's change of
gravity; below the arch the grains fall through the air, and the drag of that slip adds to it.

Usage: air_force_profile.py RUN [RUN ...] [--window 0.03,0.08]   (prints a table per run)
"""
import argparse
import glob
import math
import os
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "beverloo_discharge"))
import run_sweep as sweep  # noqa: E402


def beta_over_solid(eps, slip, d_o, rho, mu):
    """beta / (1 - eps) of the paper's law (coupling/drag.hpp), elementwise."""
    ergun = 150 * mu * (1 - eps) / (eps * d_o ** 2) + 1.75 * rho * slip / d_o
    re = np.maximum(eps * rho * d_o * slip / mu, 1e-300)
    cd_slip = np.where(re <= 1000, 24 * mu / (eps * rho * d_o) * (1 + 0.15 * re ** 0.687), 0.44 * slip)
    wen_yu = 0.75 * cd_slip * eps * rho / d_o * eps ** -2.65
    return np.where(eps <= 0.8, ergun, wen_yu)


def profile(run, window):
    cfg = sweep.resolved(run)
    sp = cfg["particles"]["species"][0]
    d_o, rho_p = sp["d_original"], sp["density"]
    rho, mu = cfg["air"]["density"], cfg["air"].get("viscosity", 1.8e-5)
    b = cfg["walls"]["body"][0]["part"][3]["min"][0] - cfg["walls"]["body"][0]["part"][2]["max"][0]
    air = {}
    for path in glob.glob(os.path.join(run, "air_*.h5")):
        with h5py.File(path) as h:
            t = float(h.attrs["time"])
            if window[0] - 1e-9 <= t <= window[1] + 1e-9:
                air[round(t, 7)] = (h["grid/n"][:], h["grid/origin"][:], h["grid/spacing"][:], h["cells/eps"][:],
                                    h["cells/p"][:], h["cells/u"][:])
    force = mass = vol = None
    for path in glob.glob(os.path.join(run, "particles_*.h5")):
        with h5py.File(path) as h:
            t = round(float(h.attrs["time"]), 7)
            if t not in air:
                continue
            x, v, dd = h["particles/x"][:], h["particles/v"][:], h["particles/d"][:]
        n, o, dx, eps, p, u = air[t]
        nx, ny, nz = n
        over = np.abs(x[:, 0] - sweep.X_C) < b / 2
        x, v, dd = x[over], v[over], dd[over]
        i = np.clip(((x - o) / dx).astype(int), 0, [nx - 1, ny - 1, nz - 1])
        e = eps[i[:, 2], i[:, 1], i[:, 0]]
        ua = u[i[:, 2], i[:, 1], i[:, 0], :]
        slip = np.linalg.norm(v - ua, axis=1)
        V = math.pi / 6 * dd ** 3
        drag = V * beta_over_solid(e, slip, d_o, rho, mu) * (ua[:, 2] - v[:, 2])
        dpdz = np.gradient(p, dx[2], axis=0)[i[:, 2], i[:, 1], i[:, 0]]
        # The still air's gradient -rho g is carried by buoyancy; gauge gradient only.
        fp = -V * (dpdz + rho * 9.81)
        if force is None:
            force, mass, vol = np.zeros(nz), np.zeros(nz), np.zeros(nz)
            dz, zo, L = dx[2], o[2], ny * dx[1]
        np.add.at(force, i[:, 2], drag + fp)
        np.add.at(mass, i[:, 2], rho_p * V)
        np.add.at(vol, i[:, 2], V)
    if force is None:
        sys.exit(f"{run}: no particle and air snapshots at the same times in the window")
    z = zo + (np.arange(len(force)) + 0.5) * dz
    with np.errstate(invalid="ignore", divide="ignore"):
        a = force / mass
        phi = vol / (len(air) * b * L * dz)
    return z, a, phi


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--window", default="0.03,0.08")
    ap.add_argument("--zmax", type=float, default=6e-3)
    a = ap.parse_args()
    window = tuple(float(s) for s in a.window.split(","))
    for run in a.runs:
        z, acc, phi = profile(run, window)
        print(f"{run}: upward air force on the solids over the slot, per unit solid mass (window {window} s)")
        print("   z [mm]   solid fraction   a_air [m/s^2]   a_air / g")
        for zi, ai, fi in zip(z, acc, phi):
            if zi <= a.zmax and np.isfinite(ai):
                print(f"  {zi * 1e3:7.2f}   {fi:14.3f}   {ai:13.3f}   {ai / 9.81:9.3f}")


if __name__ == "__main__":
    main()
