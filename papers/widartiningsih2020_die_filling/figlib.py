"""Helpers shared by the figure scripts of this folder: reading a cgdem run folder
(config.resolved.toml, diagnostics.csv, impacts.csv, metrics.csv, the particle and air
snapshots), the paper's reference numbers, the die-filling walls in an x-z section, and
saving a small PNG.

Units: SI in the files; the figures show mm, ms or s, g/s, m/s and Pa, stated on each axis.
"""
import argparse
import csv
import os
import re
import sys
import tomllib

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
except ImportError as e:  # pragma: no cover
    sys.exit(f"error: {e}. Install Debian's python3-numpy python3-matplotlib python3-h5py "
             "and run the scripts with /usr/bin/python3 (or set PYTHON for run.sh).")


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "validation", "die_filling"))
from origin import shoe_travel  # noqa: E402

__all__ = ["InputError", "PAPER", "PAPER_PRESSURE_EVENTS", "Run", "load_runs", "by_die_type", "read_csv",
           "read_metrics", "read_particles", "read_air", "draw_walls", "save", "arg_parser", "main_guard",
           "require", "plt"]


class InputError(Exception):
    """A missing or malformed input file; the scripts print it and exit with status 1."""


# ---------------------------------------------------------------- the paper's numbers
# docs/model.md, section 6 (times in s, speeds in m/s). The paper gives the impact velocity
# of the original (l = 1) and coarse-grained (l = 2, 3) systems, none for the simply large
# case (x-4); the peak times are read from its text ("~0.19 s", "around 0.18 s").
PAPER = {
    1: {"front_time": 0.100, "impact": {"1": 0.257, "2": 0.251, "3": 0.266},
        "peak_time": 0.19, "snapshot_times": [0.10, 0.15, 0.19]},
    2: {"front_time": 0.116, "impact": {"1": 0.231, "2": 0.220, "3": 0.226},
        "peak_time": 0.18, "snapshot_times": [0.11, 0.15, 0.18]},
}
# Times the paper discusses for the pressure (both die types): fluctuations while the gap
# is small (die opening, closing) and the broad maximum when half the mouth is covered.
PAPER_PRESSURE_EVENTS = {"die opens": 0.05, "broad max": 0.10, "die closes": 0.25}

CASE_COLOURS = {"1": "tab:blue", "2": "tab:green", "3": "tab:red", "4": "tab:purple"}


# ---------------------------------------------------------------- reading a run folder
def require(path, what=""):
    if not os.path.isfile(path):
        hint = f" ({what})" if what else ""
        raise InputError(f"missing input file {path}{hint}")
    return path


# The unit of each column name cgdem wrote before the names carried their unit (the files
# then began with '#' lines and a column line of bare names): a file of that layout is read
# with the names of today (t -> t_s, p_A -> p_A_Pa, speed_down -> speed_down_m_s).
OLD_UNITS = {"t": "s", "mass_in_die": "kg", "transfer_rate": "kg/s", "impacts": "1", "mass_in_shoe": "kg",
             "Q_cavity": "m^3/s", "Q_shoe_walls": "m^3/s", "Q_open_mouth": "m^3/s", "bubbles": "1",
             "V_bubbles": "m^3", "V_bubble_max": "m^3", "z_bubble": "m", "z_bubble_top": "m",
             "V_bubbles_shoe": "m^3", "V_sealed": "m^3", "id": "1", "speed_down": "m/s", "mass": "kg"}


def new_name(old):
    unit = OLD_UNITS.get(old, "Pa" if old.startswith("p_") and len(old) > 2 else "1")
    return old if unit == "1" else old + "_" + unit.replace("^", "").replace("/", "_").replace(" ", "_")


def read_csv(path):
    """A cgdem CSV as {column: numpy array}: the column line first, then '#' lines (provenance,
    each column's unit and description), then the rows; or, written before, without the
    description lines and with bare names (renamed to today's names, new_name)."""
    require(path)
    with open(path, newline="") as f:
        lines = f.read().splitlines()
    rows = [r for r in csv.reader(line for line in lines if not line.startswith("#")) if r]
    if not rows:
        raise InputError(f"{path}: no header")
    names, body = rows[0], rows[1:]
    if not any(line.startswith(f"# {names[0]}: ") for line in lines):  # no descriptions: the layout before units
        names = [new_name(n) for n in names]
    try:
        data = np.array([[float(v) for v in r] for r in body], dtype=float).reshape(len(body), len(names))
    except ValueError as e:
        raise InputError(f"{path}: {e}") from e
    return {n: data[:, i] for i, n in enumerate(names)}


def read_metrics(path):
    require(path, "written by cgdem at the end of a run")
    out = {}
    with open(path, newline="") as f:
        for r in csv.reader(line for line in f if not line.startswith("#")):
            if len(r) == 2 and r[0] != "name":
                out[r[0]] = float(r[1])
    return out


class Run:
    """One cgdem run folder of a die-filling case."""

    def __init__(self, path):
        self.dir = os.path.abspath(path)
        if not os.path.isdir(self.dir):
            raise InputError(f"run folder {path} does not exist")
        cfg_path = require(os.path.join(self.dir, "config.resolved.toml"), "written by cgdem run")
        with open(cfg_path, "rb") as f:
            head = f.readline().decode()
            f.seek(0)
            self.config = tomllib.load(f)
        m = re.match(r"#\s*cgdem\s+(\S+)", head)
        self.revision = m.group(1) if m else "unknown"
        walls = self.config.get("walls", {})
        if "die_filling" not in walls:
            raise InputError(f"{cfg_path}: not a die-filling case (no [walls.die_filling])")
        self.die = walls["die_filling"]
        self.die_type = int(self.die["die_type"])
        sp = self.config["particles"]["species"][0]
        self.ratio = int(round(sp["ratio"]))
        self.d_original = float(sp["d_original"])
        self.d_parcel = self.ratio * self.d_original
        # Table 2: x-1 original 125 um, x-2 / x-3 coarse-grained, x-4 simply large 375 um.
        if self.ratio > 1:
            idx = str(self.ratio)
        else:
            idx = "1" if self.d_original < 200e-6 else "4"
        self.case_index = idx
        self.case = f"{self.die_type}-{idx}"
        kind = {"1": "original", "4": "simply large"}.get(idx, "coarse-grained")
        self.label = f"Case {self.case} (l = {self.ratio}, {self.d_parcel * 1e6:.0f} um, {kind})"
        self.colour = CASE_COLOURS.get(idx, "k")
        self.diag = self.config.get("diagnostics", {})

    def file(self, name, what=""):
        return require(os.path.join(self.dir, name), what)

    def diagnostics(self):
        return read_csv(self.file("diagnostics.csv", "written while cgdem runs a die-filling case"))

    def impacts(self):
        return read_csv(self.file("impacts.csv", "written by cgdem at the end of a run"))

    def metrics(self):
        return read_metrics(os.path.join(self.dir, "metrics.csv"))

    # -- snapshots
    def snapshots(self, prefix):
        """[(time, h5 path)] from PREFIX.xdmf ('particles' or 'air'), in time order."""
        xdmf = self.file(prefix + ".xdmf", "snapshot index written by cgdem")
        with open(xdmf) as f:
            text = f.read()
        out = []
        for grid in re.findall(r"<Grid Name=\"step_\d+\".*?</Grid>", text, re.S):
            t = re.search(r"<Time Value=\"([^\"]+)\"", grid)
            h5 = re.search(r"Format=\"HDF\">([^:<]+):", grid)
            if t and h5:
                out.append((float(t.group(1)), os.path.join(self.dir, h5.group(1))))
        if not out:
            raise InputError(f"{xdmf}: no snapshots listed")
        return sorted(out)

    def snapshot_at(self, prefix, t, tol=0.5e-3):
        snaps = self.snapshots(prefix)
        ts = np.array([s[0] for s in snaps])
        i = int(np.argmin(abs(ts - t)))
        if abs(ts[i] - t) > tol:
            raise InputError(f"{self.dir}: no {prefix} snapshot within {tol * 1e3:g} ms of t = {t:g} s "
                             f"(have {ts.min():.3f} .. {ts.max():.3f} s every "
                             f"{np.median(np.diff(ts)) if len(ts) > 1 else 0:.3g} s)")
        return snaps[i][0], require(snaps[i][1], f"listed in {prefix}.xdmf")

    def last_snapshot(self, prefix):
        t, path = self.snapshots(prefix)[-1]
        return t, require(path, f"listed in {prefix}.xdmf")

    # -- geometry
    def shoe_shift(self, t):
        """Displacement of the shoe along x at time t [m] from its place at t = 0, where
        cavity_x0 puts it (validation/die_filling/origin.py's shoe_travel, the one copy of
        cgdem's shoe motion in the scripts)."""
        return shoe_travel(self.die, t)

    def y_mid(self):
        return self.die["mouth_y0"] + 0.5 * self.die["mouth_width"]


def load_runs(paths):
    runs = [Run(p) for p in paths]
    seen = {}
    for r in runs:
        if r.case in seen:
            raise InputError(f"two runs of Case {r.case}: {seen[r.case]} and {r.dir}")
        seen[r.case] = r.dir
    return sorted(runs, key=lambda r: (r.die_type, r.case_index))


def by_die_type(runs):
    out = {}
    for r in runs:
        out.setdefault(r.die_type, []).append(r)
    return dict(sorted(out.items()))


def read_particles(path):
    import h5py

    with h5py.File(require(path), "r") as f:
        g = f["particles"]
        return {"x": g["x"][...], "d": g["d"][...], "v": g["v"][...] if "v" in g else None}


def read_air(path):
    """Cell-centred air fields, arrays indexed [k, j, i] (z, y, x); u has a last axis of 3."""
    import h5py

    with h5py.File(require(path), "r") as f:
        c = f["cells"]
        return {"n": f["grid/n"][...], "origin": f["grid/origin"][...], "h": f["grid/spacing"][...],
                "u": c["u"][...], "alpha": c["alpha"][...], "eps": c["eps"][...]}


# ---------------------------------------------------------------- drawing
WALL_STYLE = dict(facecolor="0.75", edgecolor="0.35", linewidth=0.6, zorder=1)


def draw_walls(ax, run, t):
    """The walls cut by the plane y = y_mid, in mm: table with the die mouth, step, floor,
    and the shoe's left and right walls at time t."""
    d = run.die
    mm = 1e3
    top, deep, shallow = d["table_top"], d["deep_depth"], d["shallow_depth"]
    x0, x1 = d["mouth_x0"], d["mouth_x0"] + d["mouth_length"]
    lo, hi = d["domain_min"][0], d["domain_max"][0]
    z_deep = top - deep
    z_floor = z_deep - d["floor_thickness"]
    rects = [
        (lo, z_floor, x0 - lo, top - z_floor),            # table left of the mouth
        (x1, z_floor, hi - x1, top - z_floor),            # table right of the mouth
        (x0, max(d["domain_min"][2], z_floor), x1 - x0, z_deep - max(d["domain_min"][2], z_floor)),  # die floor
    ]
    xs = d["mouth_length"] * d["step_fraction"]
    if xs > 0 and shallow < deep:
        sx = x0 if run.die_type == 1 else x1 - xs
        rects.append((sx, z_deep, xs, deep - shallow))  # raised floor of the shallow section
    s = run.shoe_shift(t)
    c0 = d["cavity_x0"] + s
    c1 = c0 + d["cavity_size"][0]
    w, z0, z1 = d["shoe_wall"], top + d["shoe_gap"], top + d["cavity_size"][2]
    rects += [(c0 - w, z0, w, z1 - z0), (c1, z0, w, z1 - z0)]
    for x, z, dx, dz in rects:
        ax.add_patch(Rectangle((x * mm, z * mm), dx * mm, dz * mm, **WALL_STYLE))


def save(fig, path, dpi=110):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=dpi)
    kb = os.path.getsize(path) / 1024
    print(f"wrote {path} ({kb:.0f} kB)")


def arg_parser(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("runs", nargs="+", metavar="RUN_DIR",
                   help="cgdem run folders of die-filling cases (each with config.resolved.toml)")
    p.add_argument("-o", "--outdir", default=".", help="folder for the PNG files (default: .)")
    return p


def main_guard(main):
    """Run main(); an InputError becomes a one-line message and exit status 1."""
    try:
        main()
    except InputError as e:
        sys.exit(f"error: {e}")
