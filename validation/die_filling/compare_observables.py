#!/usr/bin/env python3
"""Compare runs of one die-filling case (metrics.csv, diagnostics.csv) against a reference run,
e.g. the same case on several MPI ranks against one process (docs/scale_out.md).

usage: compare_observables.py REF_DIR RUN_DIR [RUN_DIR ...]

For each run: the metrics of the final report (fill mass, front time, impact velocity, peak
transfer rate, peak and mean gauge pressure at A, B, C) as relative differences from the
reference, and the time series of diagnostics.csv (transfer rate, p_A, p_B, p_C) on the
reference's rows: the rms of the difference over the filling (t >= 0) relative to the
reference's largest |value|. Mean pressures are compared relative to the larger of the
mean and the peak (the mean at A is close to 0). Exits 1 when a figure exceeds its
tolerance (below)."""
import math, sys

TOL = {  # relative, unless noted
    "fill_mass_kg": 0.02,
    "front_time_s": 0.002,           # absolute [s]
    "mean_impact_velocity_m_s": 0.10,
    "transfer_rate_peak_kg_s": 0.10,
    "p_A_peak_Pa": 0.10, "p_B_peak_Pa": 0.10, "p_C_peak_Pa": 0.10,
    "p_A_mean_Pa": 0.10, "p_B_mean_Pa": 0.10, "p_C_mean_Pa": 0.10,
}
SERIES_TOL = {"transfer_rate_kg_s": 0.10, "p_A_Pa": 0.05, "p_B_Pa": 0.05, "p_C_Pa": 0.05}


SMOOTH_TOL = {"transfer_rate_kg_s": 0.05, "p_A_Pa": 0.05, "p_B_Pa": 0.05, "p_C_Pa": 0.05}


def smooth(t, v, width=5e-3):
    """Centred moving average over `width` of the rows with t >= 0: {t: mean}."""
    out, lo, hi, acc = {}, 0, 0, 0.0
    pts = [(a, b) for a, b in zip(t, v) if a >= 0 and not math.isnan(b)]
    for a, _ in pts:
        while hi < len(pts) and pts[hi][0] <= a + width / 2:
            acc += pts[hi][1]
            hi += 1
        while pts[lo][0] < a - width / 2:
            acc -= pts[lo][1]
            lo += 1
        out[a] = acc / (hi - lo)
    return out


def interp(m, t):
    keys = sorted(m) if not hasattr(interp, "cache") or interp.cache[0] is not m else interp.cache[1]
    interp.cache = (m, keys)
    import bisect
    j = bisect.bisect_right(keys, t)
    if j == 0 or j >= len(keys):
        return None
    a, b = keys[j - 1], keys[j]
    w = (t - a) / (b - a)
    return (1 - w) * m[a] + w * m[b]


def metrics(d):
    out = {}
    for line in open(d + "/metrics.csv"):
        k, _, v = line.strip().partition(",")
        if k != "name":
            out[k] = float(v)
    return out


# The unit of each column name cgdem wrote before the names carried their unit (the files
# then began with '#' lines and a column line of bare names): such files are read with the
# names of today (t -> t_s, mass_in_die -> mass_in_die_kg, p_A -> p_A_Pa).
OLD_UNITS = {"t": "s", "mass_in_die": "kg", "transfer_rate": "kg/s", "mass_in_shoe": "kg", "Q_cavity": "m^3/s",
             "Q_shoe_walls": "m^3/s", "Q_open_mouth": "m^3/s", "V_bubbles": "m^3", "V_bubble_max": "m^3",
             "z_bubble": "m", "z_bubble_top": "m", "V_bubbles_shoe": "m^3", "V_sealed": "m^3"}


def new_name(old):
    unit = OLD_UNITS.get(old, "Pa" if old.startswith("p_") and len(old) > 2 else None)
    return old if unit is None else old + "_" + unit.replace("^", "").replace("/", "_")


def series(d):
    """diagnostics.csv by column: the column line first, then '#' lines and rows (or, written
    before, '#' lines, then the column line with bare names)."""
    lines = [l.strip() for l in open(d + "/diagnostics.csv") if l.strip()]
    rows = [l for l in lines if not l.startswith("#")]
    head = rows[0].split(",")
    if not any(l.startswith(f"# {head[0]}: ") for l in lines):  # no descriptions: before units
        head = [new_name(h) for h in head]
    data = {h: [] for h in head}
    for r in rows[1:]:
        for h, v in zip(head, r.split(",")):
            data[h].append(float(v))
    return data


def computed(series):
    """False when a column holds no number (a pressure of a run without air)."""
    return any(not math.isnan(v) for v in series)


def main():
    ref, runs = sys.argv[1], sys.argv[2:]
    mr, sr = metrics(ref), series(ref)
    bad = False
    for run in runs:
        m, s = metrics(run), series(run)
        print(f"{run} vs {ref}")
        for k, tol in TOL.items():
            a, b = mr.get(k), m.get(k)
            a = None if a is not None and math.isnan(a) else a  # NaN: how older runs wrote it
            b = None if b is not None and math.isnan(b) else b
            if a is None or b is None:  # metrics.csv leaves out what it cannot compute (no air)
                same = a is None and b is None
                bad |= not same
                where = "either run" if same else ("the reference" if a is None else "this run")
                print(f"  {k:28s} not computed in {where}: {'ok' if same else 'MISMATCH'}")
                continue
            if k == "front_time_s":
                d = abs(b - a)
            elif k.endswith("_mean_Pa"):  # a mean near 0 (cell A): relative to the cell's peak
                d = abs(b - a) / max(abs(mr.get(k.replace("_mean", "_peak"), a)), abs(a), 1e-300)
            else:
                d = abs(b - a) / max(abs(a), 1e-300)
            ok = d <= tol
            bad |= not ok
            print(f"  {k:28s} {a:12.6g} {b:12.6g}  diff {d:9.3e} (tol {tol:g}{' s' if k == 'front_time_s' else ''}) "
                  f"{'ok' if ok else 'EXCEEDS'}")
        t_ref, t_run = sr["t_s"], s["t_s"]
        for k, tol in SERIES_TOL.items():
            if not (computed(sr[k]) and computed(s[k])):
                same = computed(sr[k]) == computed(s[k])
                bad |= not same
                print(f"  series {k:21s} not computed in {'either run' if same else 'one run'}: "
                      f"{'ok' if same else 'MISMATCH'}")
                continue
            num, n, scale = 0.0, 0, max(abs(v) for v in sr[k])
            j = 0
            for i, t in enumerate(t_ref):
                # The rows fall at the fluid steps, which the CFL limit places differently in
                # each run: the run's series is interpolated linearly to the reference's times.
                while j + 1 < len(t_run) and t_run[j + 1] < t:
                    j += 1
                if t < 0 or j + 1 >= len(t_run) or not (t_run[j] <= t <= t_run[j + 1]):
                    continue
                w = (t - t_run[j]) / (t_run[j + 1] - t_run[j])
                v = (1 - w) * s[k][j] + w * s[k][j + 1]
                if math.isnan(sr[k][i]) or math.isnan(v):
                    continue
                num += (v - sr[k][i]) ** 2
                n += 1
            rms = math.sqrt(num / max(n, 1)) / scale
            ok = rms <= tol and n > 0
            bad |= not ok
            print(f"  series {k:21s} rms diff {rms:9.3e} of max |ref| {scale:.4g} over {n} rows (tol {tol:g}) "
                  f"{'ok' if ok else 'EXCEEDS'}")
        # The same on the 5 ms moving averages (t >= 0): the part of a fluctuating signal that
        # round-off does not decorrelate. Also the reference's own fluctuation (raw minus
        # smoothed, rms over t >= 0), the scale of what two decorrelated runs differ by.
        for k, tol in SMOOTH_TOL.items():
            if not (computed(sr[k]) and computed(s[k])):
                continue  # said above
            ra, rb = smooth(sr["t_s"], sr[k]), smooth(s["t_s"], s[k])
            fa, fb = max(abs(v) for v in ra.values()), max(abs(v) for v in rb.values())
            d_peak = abs(fb - fa) / fa
            diffs, fl = [], []
            for t, v in ra.items():
                w = interp(rb, t)
                if w is not None:
                    diffs.append((w - v) ** 2)
            for t, v in zip(sr["t_s"], sr[k]):
                if t >= 0 and t in ra:
                    fl.append((v - ra[t]) ** 2)
            rms = math.sqrt(sum(diffs) / max(len(diffs), 1)) / fa
            fluct = math.sqrt(sum(fl) / max(len(fl), 1)) / fa
            ok = rms <= tol and d_peak <= 2 * tol
            bad |= not ok
            print(f"  5 ms average {k:15s} peak {fa:.4g} vs {fb:.4g} (diff {d_peak:.3e}, tol {2 * tol:g}); rms diff "
                  f"{rms:.3e} of the peak (tol {tol:g}); raw fluctuation of the reference {fluct:.3e} of the peak "
                  f"{'ok' if ok else 'EXCEEDS'}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
