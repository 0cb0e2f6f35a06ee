#!/usr/bin/python3
"""Figs. 3/4 (die type 1) and 8/9 (die type 2) of the paper: particle locations and air
velocity vectors in a vertical x-z section through the middle of the die (y = y_mid), in
the die region and in the shoe region, at the paper's times (type 1: 0.10, 0.15, 0.19 s;
type 2: 0.11, 0.15, 0.18 s) and at the final state (the run's last snapshot).

Reads, per run: config.resolved.toml, particles.xdmf + particles_*.h5, air.xdmf + air_*.h5.
Particles: every parcel whose centre lies within the slab |y - y_mid| <= slab/2, drawn at
its diameter. Air: cell-centred velocity (u_x, u_z) averaged over the two cell layers
either side of y_mid (the same slab), every second cell, hidden in cells that are more
than half wall (alpha > 0.5). One row per case, one column per time; one PNG per die type
and region:

  fig3_die_region_type1.png  fig4_shoe_region_type1.png
  fig8_die_region_type2.png  fig9_shoe_region_type2.png
"""
import os

import numpy as np
from matplotlib.collections import EllipseCollection

import figlib as fl
from figlib import plt

FIG_NUMBERS = {1: (3, 4), 2: (8, 9)}
MM = 1e3


def window(run, region, t):
    """(x0, x1, z0, z1) of the panel in m."""
    d = run.die
    top = d["table_top"]
    if region == "die":
        x0, x1 = d["mouth_x0"] - 3e-3, d["mouth_x0"] + d["mouth_length"] + 3e-3
        return x0, x1, top - d["deep_depth"] - 1e-3, top + 4e-3
    c0 = d["cavity_x0"] + run.shoe_shift(t)
    c1 = c0 + d["cavity_size"][0]
    w = d["shoe_wall"]
    return c0 - w - 1e-3, c1 + w + 1e-3, top - 3e-3, top + d["cavity_size"][2] + 2e-3


def draw_particles(ax, run, path, slab, box):
    p = fl.read_particles(path)
    x, d = p["x"], p["d"]
    x0, x1, z0, z1 = box
    keep = ((abs(x[:, 1] - run.y_mid()) <= 0.5 * slab) & (x[:, 0] > x0 - d) & (x[:, 0] < x1 + d)
            & (x[:, 2] > z0 - d) & (x[:, 2] < z1 + d))
    if keep.any():
        ax.add_collection(EllipseCollection(d[keep] * MM, d[keep] * MM, np.zeros(keep.sum()), units="xy",
                                            offsets=x[keep][:, [0, 2]] * MM, transOffset=ax.transData,
                                            facecolors="tab:orange", edgecolors="none", zorder=2))
    return int(keep.sum())


def draw_air(ax, run, path, box, u_ref, stride=2):
    a = fl.read_air(path)
    o, h = a["origin"], a["h"]
    nx, ny, nz = (int(v) for v in a["n"])
    # Two cell layers whose common face is y_mid (or the nearest face).
    jf = int(round((run.y_mid() - o[1]) / h[1]))
    js = [j for j in (jf - 1, jf) if 0 <= j < ny]
    u = a["u"][:, js, :, :].mean(axis=1)          # [k, i, 3]
    alpha = a["alpha"][:, js, :].mean(axis=1)     # [k, i]
    xc = o[0] + (np.arange(nx) + 0.5) * h[0]
    zc = o[2] + (np.arange(nz) + 0.5) * h[2]
    x0, x1, z0, z1 = box
    ii = np.where((xc > x0) & (xc < x1))[0][::stride]
    kk = np.where((zc > z0) & (zc < z1))[0][::stride]
    K, I = np.meshgrid(kk, ii, indexing="ij")
    ok = alpha[K, I] <= 0.5
    # An air speed u_ref is drawn 1.2 mm long (two cells, the spacing of the arrows).
    q = ax.quiver(xc[I][ok] * MM, zc[K][ok] * MM, u[K, I, 0][ok], u[K, I, 2][ok], color="tab:blue",
                  angles="xy", scale_units="xy", scale=u_ref / 1.2, width=0.006, headwidth=3.5,
                  headlength=4, zorder=3)
    speed = np.hypot(u[K, I, 0], u[K, I, 2])[ok]
    return q, float(speed.max()) if speed.size else 0.0


def figure(runs, die_type, region, slab, u_ref, outdir, times=None):
    times = times or fl.PAPER[die_type]["snapshot_times"]
    ncol = len(times) + 1
    fig, axes = plt.subplots(len(runs), ncol, figsize=(2.25 * ncol, 2.35 * len(runs) + 0.75),
                             squeeze=False, sharey=True)
    q = None
    for r, run in enumerate(runs):
        picks = [run.snapshot_at("particles", t) for t in times] + [run.last_snapshot("particles")]
        for c, (t, ppath) in enumerate(picks):
            ax = axes[r, c]
            box = window(run, region, t)
            _, apath = run.snapshot_at("air", t, tol=1e-6)
            fl.draw_walls(ax, run, t)
            n = draw_particles(ax, run, ppath, slab, box)
            q, umax = draw_air(ax, run, apath, box, u_ref)
            ax.set_xlim(box[0] * MM, box[1] * MM)
            ax.set_ylim(box[2] * MM, box[3] * MM)
            ax.set_aspect("equal")
            title = f"t = {t:.4f} s" if c < len(times) else f"final, t = {t:.4f} s"
            ax.set_title(title, fontsize=8)
            ax.text(0.02, 0.02, f"{n} parcels\nmax |(u_x, u_z)| {umax:.2f} m/s", transform=ax.transAxes, fontsize=5.5,
                    va="bottom", bbox=dict(facecolor="white", alpha=0.7, lw=0, pad=1), zorder=4)
            ax.tick_params(labelsize=6)
            if r == len(runs) - 1:
                ax.set_xlabel("x [mm]", fontsize=7)
            if c == 0:
                ax.set_ylabel(f"Case {run.case}\nz [mm]", fontsize=7)
    if q is not None:
        axes[0, -1].quiverkey(q, 0.62, 1.17, u_ref, f"air {u_ref:g} m/s", labelpos="E", coordinates="axes",
                              fontproperties={"size": 7})
    num = FIG_NUMBERS[die_type][0 if region == "die" else 1]
    where = "die region" if region == "die" else "shoe region (window moves with the shoe)"
    fig.suptitle(f"Die type {die_type}, {where}: parcels within {slab * MM / 2:g} mm of the section (orange) "
                 f"and air velocity, lab frame (blue), at y = {runs[0].y_mid() * MM:g} mm  [cf. paper Fig. {num}]",
                 fontsize=7.5)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    name = f"fig{num}_{region}_region_type{die_type}.png"
    fl.save(fig, os.path.join(outdir, name))
    plt.close(fig)


def main():
    p = fl.arg_parser(__doc__.split("\n\n")[0])
    p.add_argument("--slab", type=float, default=1.2e-3,
                   help="thickness in y of the slab of parcels drawn [m] (default 1.2e-3, two air cells)")
    p.add_argument("--u-ref", type=float, default=0.3,
                   help="air speed drawn as an arrow 1.2 mm long, the key arrow [m/s] (default 0.3)")
    p.add_argument("--region", choices=["die", "shoe", "both"], default="both")
    p.add_argument("--times", type=float, nargs="+", metavar="T",
                   help="snapshot times [s] instead of the paper's (e.g. to look at a run still going)")
    a = p.parse_args()
    runs = fl.load_runs(a.runs)
    regions = ["die", "shoe"] if a.region == "both" else [a.region]
    for die_type, group in fl.by_die_type(runs).items():
        for region in regions:
            figure(group, die_type, region, a.slab, a.u_ref, a.outdir, a.times)


if __name__ == "__main__":
    fl.main_guard(main)
