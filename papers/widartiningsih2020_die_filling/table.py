#!/usr/bin/python3
"""Prints a Markdown table of our numbers beside the paper's (docs/model.md, section 6) for
the given run folders, for README.md.

Reads, per run: config.resolved.toml, metrics.csv, diagnostics.csv and, for the wall time,
timings.csv (written by cgdem since December 2026: one group of rows per run, so a case run
in pieces from checkpoints adds its pieces' walls). A run folder without it falls back on the
run's log (RUN_DIR/../logs/<name>.log as run.sh writes it, or RUN_DIR.log): cgdem's "wall ...
s" line, the simulated span it covers (from time.start, or from the time of a --restart) and
the threads (the --threads of the logged command).
"""
import argparse
import csv
import os
import re

import numpy as np

import figlib as fl

OPEN_WINDOW = (0.06, 0.11)  # s: from just after the die opens to just after the paper's broad maximum
DIE_CLOSES = 0.25  # s: the shoe's body covers the whole mouth again (validation/die_filling/README.md)


def find_log(run):
    name = os.path.basename(run.dir)
    for path in (os.path.join(os.path.dirname(run.dir), "logs", name + ".log"), run.dir + ".log"):
        if os.path.isfile(path):
            return path
    return None


def log_facts(path):
    facts = {"wall_s": None, "threads": None, "revision": None, "restart_t": None}
    if not path:
        return facts
    with open(path, errors="replace") as f:
        text = f.read()
    m = re.findall(r"DEM steps \d+, wall ([0-9.]+) s", text)
    facts["wall_s"] = float(m[-1]) if m else None
    m = re.findall(r"--threads (\d+)", text)
    facts["threads"] = int(m[-1]) if m else None
    m = re.findall(r"^cgdem (\S+):", text, re.M)  # the last run of the log (a rerun appends)
    facts["revision"] = m[-1] if m else None
    m = re.findall(r"restarting from \S+ at t = (\S+) s", text)
    facts["restart_t"] = float(m[-1]) if m else None
    return facts


def timing_facts(run_dir):
    """From RUN_DIR/timings.csv, the runs (pieces) that made the folder: their number, the summed
    wall and set-up times, the span they cover, their threads and revisions, the peak memory;
    None without the file."""
    path = os.path.join(run_dir, "timings.csv")
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    whole = [r for r in rows if r["group"] == "run"]
    wall = [r for r in whole if r["phase"] == "wall"]
    if not wall:
        return None
    return {"pieces": len(wall),
            "wall_s": sum(float(r["seconds_s"]) for r in wall),
            "set_up_s": sum(float(r["seconds_s"]) for r in whole if r["phase"] == "set_up"),
            "t_start": min(float(r["t_start_s"]) for r in wall),
            "t_end": max(float(r["t_s"]) for r in wall),
            "threads": sorted({int(r["threads"]) for r in wall}),
            "revisions": list(dict.fromkeys(r["revision"][:7] for r in wall)),
            "peak_gib": max(float(r["peak_rss_MiB"]) for r in wall) / 1024}


def run_cell(run, m):
    """The table's last row: how the run was made and what it cost."""
    tf = timing_facts(run.dir)
    if tf:
        pieces = f" in {tf['pieces']} pieces" if tf["pieces"] > 1 else ""
        return (f"commit{'s' if len(tf['revisions']) > 1 else ''} {', '.join(tf['revisions'])}, "
                f"{'/'.join(str(t) for t in tf['threads'])} threads, wall {tf['wall_s']:.0f} s{pieces} "
                f"(+ {tf['set_up_s']:.0f} s set-up) for t = {0.0 if abs(tf['t_start']) < 1e-9 else tf['t_start']:g}"
                f" to {tf['t_end']:.2f} s, peak memory {tf['peak_gib']:.2f} GiB")
    log = find_log(run)
    facts = log_facts(log)
    start = facts["restart_t"] if facts["restart_t"] is not None else run.config["time"]["start"]
    if not log:
        return f"commit {run.revision[:7]}, no log found (wall time, threads unknown)"
    return (f"commit {(facts['revision'] or run.revision)[:7]}, "
            f"{facts['threads'] if facts['threads'] else '?'} threads, "
            f"wall {fmt(facts['wall_s'], '{:.0f}', ' s')} for t = {0.0 if abs(start) < 1e-9 else start:g}"
            f" to {m.get('end_time_s', np.nan):.2f} s")


def fmt(v, f="{:.3f}", unit=""):
    return "n/a" if v is None or not np.isfinite(v) else f.format(v) + unit


def column(run):
    m = run.metrics()
    d = run.diagnostics()
    paper = fl.PAPER[run.die_type]
    tp = paper["peak_time"]
    t, mass = d["t_s"], d["mass_in_die_kg"]
    final = float(mass[-1])
    # A run stopped before the die closes (the original systems, run in part: issue #20)
    # has no final state: what needs one says where the run ends instead.
    end = float(m.get("end_time_s", t[-1]))
    cut = f"run ends at {end:.2f} s" if end < DIE_CLOSES - 1e-9 else None
    upto = f" (run to {end:.2f} s)" if cut else ""
    full = t[np.argmax(mass >= 0.99 * final)] if final > 0 else np.nan
    at_tp = float(np.interp(tp, t, mass)) if t[0] <= tp <= t[-1] else np.nan
    ours = {
        "front": fmt(m.get("front_time_s"), "{:.4f}", " s"),
        "impact": fmt(m.get("mean_impact_velocity_m_s"), "{:.3f}", " m/s"),
        "rate": (fmt(m.get("transfer_rate_peak_kg_s", np.nan) * 1e3, "{:.1f}", " g/s") + " at "
                 + fmt(m.get("transfer_rate_peak_time_s"), "{:.3f}", " s") + upto),
        "full": fmt(full, "{:.3f}", " s"),
        "at_tp": fmt(at_tp * 1e3, "{:.3f}", " g") + (f" ({at_tp / final:.0%} of the final)" if final > 0 else ""),
        "fill": fmt(final * 1e3, "{:.3f}", " g") + " at " + fmt(float(t[-1]), "{:.2f}", " s"),
    }
    # The die's pressure after it opens: the broad maximum (mean of the cells over
    # OPEN_WINDOW) and each cell's largest value after it (the entrapped air). metrics.csv's
    # peaks cover t >= 0 and so include the sealed die's swings before it opens
    # (validation/die_filling/README.md, "Artifact").
    if all(f"p_{c}_Pa" in d for c in "ABC"):
        mean = (d["p_A_Pa"] + d["p_B_Pa"] + d["p_C_Pa"]) / 3
        w = (t >= OPEN_WINDOW[0]) & (t <= OPEN_WINDOW[1])
        ours["p_open"] = (fmt(float(mean[w].max()), "{:.1f}", " Pa") + " at " + fmt(float(t[w][np.argmax(mean[w])]),
                          "{:.3f}", " s")) if w.any() else "n/a"
        late = t > OPEN_WINDOW[1]
        for c in "ABC":
            v = d[f"p_{c}_Pa"][late]
            ours["p_" + c] = (fmt(float(v.max()), "{:.1f}", " Pa") + " at " + fmt(float(t[late][np.argmax(v)]), "{:.3f}", " s")
                              + upto if late.any() else "n/a")
    else:
        ours["p_open"] = "no air"
        for c in "ABC":
            ours["p_" + c] = "no air"
    shoe = d.get("mass_in_shoe_kg")
    ours["shoe"] = fmt(float(shoe[-1]) * 1e3, "{:.3f}", " g") if shoe is not None else "n/a"
    if cut:
        for key in ("full", "fill", "shoe"):
            ours[key] = cut
        ours["at_tp"] = fmt(at_tp * 1e3, "{:.3f}", " g") if np.isfinite(at_tp) else cut
    ours["run"] = run_cell(run, m)
    ref = paper["impact"].get(run.case_index)
    theirs = {
        "front": f"{paper['front_time']:.3f} s",
        "impact": f"{ref:.3f} m/s" if ref else "not given",
        "rate": f"maximum at ~{tp:.2f} s (value not in the text)",
        "full": f"still filling at {tp:.2f} s",
        "at_tp": "still filling (rate at its maximum)",
        "fill": "not given",
        "run": "",
    }
    theirs["p_open"] = "broad maximum at 0.10 s (value not in the text)"
    theirs["shoe"] = "powder left in the shoe (text on Figs. 4, 9; amount not given)"
    for c in "ABC":
        theirs["p_" + c] = f"sharp peak at ~{tp:.2f} s (value not in the text)"
    return ours, theirs


LABELS = [
    ("front", "powder front reaches the die floor"),
    ("impact", "mean impact velocity (arrivals in the first 5 ms)"),
    ("rate", "largest mass transfer rate (5 ms window)"),
    ("full", "die holds 99 % of its final powder"),
    ("at_tp", "powder in the die at the paper's peak time"),
    ("p_open", "die pressure (mean of A, B, C): largest over 0.06-0.11 s"),
    ("p_A", "cell A: largest gauge pressure after 0.11 s"),
    ("p_B", "cell B: largest gauge pressure after 0.11 s"),
    ("p_C", "cell C: largest gauge pressure after 0.11 s"),
    ("fill", "powder in the die at the end"),
    ("shoe", "powder left in the shoe at the end"),
    ("run", "run"),
]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", metavar="RUN_DIR")
    a = p.parse_args()
    runs = fl.load_runs(a.runs)
    cols = [(run, *column(run)) for run in runs]
    head = ["quantity"]
    for run, _, _ in cols:
        head += [f"ours, Case {run.case}", f"paper, Case {run.case}"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for key, label in LABELS:
        cells = [label]
        for _, ours, paper in cols:
            cells += [ours[key], paper[key]]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    fl.main_guard(main)
