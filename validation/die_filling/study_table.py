#!/usr/bin/env python3
"""The die-filling observables of the paper (section 4) from one or more run folders, as a
Markdown table: one column per run. The geometry study of README.md is made of these.

    validation/die_filling/study_table.py LABEL=RUN_DIR [LABEL=RUN_DIR ...]

Reads each run's diagnostics.csv and metrics.csv (and shoe_surface.csv when present).
Rows: front time and impact velocity, mass in the die at fixed times, when 99 % of the
powder is in the die, the transfer rate's maximum, the die pressure (mean of cells A, B, C)
before 0.10 s, the release (when it falls below half its 0.06-0.10 s mean), cell B's peak, the
largest entrapped-air volume, where the die's air left (integrated path fluxes), the powder
left in the shoe when the die closes and at the end. Needs numpy only.
"""
import sys

import numpy as np


# Files written before the column names carried their unit are read under today's names
# (t -> t_s, mass_in_die -> mass_in_die_kg, p_A -> p_A_Pa): the mapping of
# compare_observables.py beside this script.
from compare_observables import new_name  # noqa: E402


def read_csv(path):
    """Columns by name: the column line first, then '#' lines and rows (or, written before,
    '#' lines, then the column line with bare names)."""
    with open(path) as f:
        all_lines = f.readlines()
    lines = [l for l in all_lines if not l.startswith("#")]
    names = lines[0].strip().split(",")
    if not any(l.startswith(f"# {names[0]}: ") for l in all_lines):  # no descriptions: before units
        names = [new_name(n) for n in names]
    rows = [l.strip().split(",") for l in lines[1:] if l.strip()]
    return {n: np.array([float(r[c]) for r in rows]) for c, n in enumerate(names)}


def metrics(path):
    out = {}
    with open(path) as f:
        for line in f:
            k, _, v = line.strip().partition(",")
            if k != "name":
                out[k] = float(v)
    return out


def at(d, col, t):
    i = int(np.argmin(abs(d["t_s"] - t)))
    return d[col][i] if abs(d["t_s"][i] - t) < 1e-3 else float("nan")


def column(run_dir):
    d = read_csv(run_dir + "/diagnostics.csv")
    m = metrics(run_dir + "/metrics.csv")
    t = d["t_s"]
    v = {}
    v["front reaches the die floor [s]"] = f"{m.get('front_time_s', float('nan')):.4f}"
    v["mean impact velocity [m/s]"] = f"{m.get('mean_impact_velocity_m_s', float('nan')):.3f}"
    for tt in (0.08, 0.10, 0.12, 0.14, 0.16, 0.18):
        v[f"mass in the die at {tt:.2f} s [g]"] = f"{1e3 * at(d, 'mass_in_die_kg', tt):.3f}"
    ok = t >= 0
    i = int(np.argmax(np.where(ok, d["transfer_rate_kg_s"], -1)))
    total = m.get("solid_mass_kg", float("nan"))   # all the powder, so that a run stopped early reads "not by"
    j99 = np.nonzero(d["mass_in_die_kg"] >= 0.99 * total)[0]
    v["die holds 99 % of all the powder [s]"] = (
        "—" if not np.isfinite(total) else f"{t[j99[0]]:.3f}" if j99.size else f"not by {t[-1]:.3f}")
    v["transfer-rate maximum [g/s] at [s]"] = f"{1e3 * d['transfer_rate_kg_s'][i]:.2f} at {t[i]:.3f}"
    cells = [c for c in ("p_A_Pa", "p_B_Pa", "p_C_Pa") if c in d]
    if cells and np.isfinite(d[cells[0]]).any():
        p = np.mean([d[c] for c in cells], axis=0)
        w = (t >= 0.05) & (t <= 0.11)
        j = int(np.argmax(np.where(w, p, -np.inf)))
        v["die pressure (mean of A, B, C) at 0.08 / 0.10 s [Pa]"] = f"{at(dict(t_s=t, p=p), 'p', 0.08):.1f} / {at(dict(t_s=t, p=p), 'p', 0.10):.1f}"
        v["its maximum over 0.05-0.11 s [Pa] at [s]"] = f"{p[j]:.1f} at {t[j]:.3f}"
        # The release: the first time after 0.10 s that the die's mean pressure falls below
        # half of its mean over 0.06-0.10 s (after the pre-opening artifact, before any
        # break-through). Unlike the bubble census it needs no resolved bubble, so it reads
        # alike on every grid.
        plateau = float(np.mean(p[(t >= 0.06) & (t <= 0.10)]))
        below = np.nonzero((t > 0.10) & (p < 0.5 * plateau))[0]
        v["die pressure below half its 0.06-0.10 s mean [Pa], first after 0.10 s [s]"] = (
            f"{plateau:.1f}, {t[below[0]]:.3f}" if below.size else f"{plateau:.1f}, never")
        late = t >= 0.11
        k = int(np.argmax(np.where(late, d["p_B_Pa"], -np.inf)))
        v["cell B peak after 0.11 s [Pa] at [s]"] = f"{d['p_B_Pa'][k]:.1f} at {t[k]:.3f}"
    else:
        v["die pressure (mean of A, B, C) at 0.08 / 0.10 s [Pa]"] = "—"
    if "V_bubble_max_m3" in d and np.isfinite(d["V_bubble_max_m3"]).any():
        vb = np.where(ok & np.isfinite(d["V_bubble_max_m3"]), d["V_bubble_max_m3"], 0)
        i = int(np.argmax(vb))
        v["largest entrapped air [mm^3] at [s]"] = f"{1e9 * vb[i]:.0f} at {t[i]:.3f}"
        vs = np.where(ok & np.isfinite(d["V_bubbles_shoe_m3"]), d["V_bubbles_shoe_m3"], 0)
        i = int(np.argmax(vs))
        v["bubble air above the table top, max [mm^3] at [s]"] = f"{1e9 * vs[i]:.1f} at {t[i]:.3f}"
    if "Q_cavity_m3_s" in d and np.isfinite(d["Q_cavity_m3_s"]).any():
        dt = np.diff(t, prepend=t[0])
        tot = {k: float(np.nansum(np.where(ok, d[k], 0) * dt)) for k in ("Q_cavity_m3_s", "Q_shoe_walls_m3_s", "Q_open_mouth_m3_s")}
        v["air out of the die via cavity / under walls / open mouth [mm^3]"] = " / ".join(
            f"{1e9 * tot[k]:.0f}" for k in ("Q_cavity_m3_s", "Q_shoe_walls_m3_s", "Q_open_mouth_m3_s"))
    if "mass_in_shoe_kg" in d:
        v["powder in the shoe at 0.25 s / end [g]"] = f"{1e3 * at(d, 'mass_in_shoe_kg', 0.25):.3f} / {1e3 * d['mass_in_shoe_kg'][-1]:.3f}"
    v["powder in the die at the end [g] (t_end [s])"] = f"{1e3 * d['mass_in_die_kg'][-1]:.3f} ({t[-1]:.3f})"
    return v


def main(argv):
    if not argv:
        sys.exit(__doc__)
    labels, cols = [], []
    for a in argv:
        label, _, run = a.partition("=")
        if not run:
            label, run = a.rstrip("/").split("/")[-1], a
        labels.append(label)
        cols.append(column(run))
    keys = list(dict.fromkeys(k for c in cols for k in c))
    print("| quantity | " + " | ".join(labels) + " |")
    print("|---|" + "---|" * len(labels))
    for k in keys:
        print(f"| {k} | " + " | ".join(c.get(k, "—") for c in cols) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
