#!/usr/bin/env python3
"""Steps every die-filling case of this folder with the implicit drag coupling
(air.coupling = "implicit", KINSOL) through `cgdem run`, for a short window, and tabulates what
the nonlinear solver did: solves, mean iterations and air steps per fluid step, the most
iterations of a step, the largest accepted residual, the pressure solver's mean iterations and
the wall time. A run that fails (a KINSOL failure stops the run with a located message) is a
row with its exit code and the message.

    validation/die_filling/implicit_all_cases.py CGDEM OUT_DIR [--end T] [--dt-fluid DT]
        [--threads N] [--jobs J] [--cases 1_1,2_3,...]

The case files are run as they are, with only the coupling, the end time, the fluid step (when
given) and the output folder overridden. Writes OUT_DIR/implicit_all_cases.md and .csv and
keeps each run's folder and log. Standard library only.
"""
import argparse
import concurrent.futures as cf
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = ["1_1", "1_2", "1_3", "1_4", "2_1", "2_2", "2_3", "2_4"]


def parse_log(text):
    """The figures of one run's log (None where the line is missing)."""
    r = {}
    m = re.search(r"cgdem (\S+): (\d+) particles", text)
    r["revision"], r["parcels"] = (m.group(1), int(m.group(2))) if m else (None, None)
    m = re.search(r"implicit drag: (\d+) nonlinear solves, ([\d.]+) iterations and ([\d.]+) air steps "
                  r"per fluid step \(at most (\d+)\), largest accepted residual ([\d.e+-]+) m/s", text)
    if m:
        r["solves"], r["iterations_mean"], r["air_steps_mean"] = int(m.group(1)), float(m.group(2)), float(m.group(3))
        r["iterations_max"], r["residual_max_m_s"] = int(m.group(4)), float(m.group(5))
    m = re.search(r"fluid steps (\d+), mean pressure iterations per step ([\d.]+), unconverged solves (\d+)", text)
    if m:
        r["fluid_steps"], r["pressure_iterations_mean"], r["pressure_unconverged"] = (
            int(m.group(1)), float(m.group(2)), int(m.group(3)))
    m = re.search(r"DEM steps (\d+), wall ([\d.]+) s", text)
    if m:
        r["dem_steps"], r["wall_s"] = int(m.group(1)), float(m.group(2))
    m = re.search(r"particles \d+ \(left the domain: (\d+), centre inside a wall: (\d+)\)", text)
    if m:
        r["escaped"] = int(m.group(1)) + int(m.group(2))
    m = re.search(r"state digest (\S+) at t = (\S+) s", text)
    if m:
        r["digest"], r["t_end_s"] = m.group(1), float(m.group(2))
    return r


def run_case(args, case):
    out = os.path.join(args.out, f"case_{case}")
    cmd = [args.cgdem, "run", os.path.join(HERE, f"case_{case}.toml"), "--threads", str(args.threads),
           "--output", out, "--set", "air.coupling=implicit", "--set", f"time.end={args.end}"]
    if args.dt_fluid:
        cmd += ["--set", f"air.dt_max={args.dt_fluid}"]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    text = p.stdout + p.stderr
    with open(out + ".log", "w") as f:
        f.write(" ".join(cmd) + "\n" + text)
    r = parse_log(text)
    r.update(case=case.replace("_", "-"), exit_code=p.returncode, elapsed_s=time.time() - t0)
    if p.returncode != 0:
        err = [l for l in text.splitlines() if "error" in l.lower()]
        r["message"] = err[-1] if err else text.strip().splitlines()[-1:]
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cgdem")
    ap.add_argument("out")
    ap.add_argument("--end", type=float, default=-0.058, help="end time, s (the cases start at -0.06 s)")
    ap.add_argument("--dt-fluid", default=None, help="fluid step, s (default: the case file's)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2, help="runs at once")
    ap.add_argument("--cases", default=",".join(CASES))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    cases = args.cases.split(",")
    # the largest cases first, so two jobs finish together
    order = sorted(cases, key=lambda c: (c.endswith("_1") is False, c))
    with cf.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        rows = {r["case"]: r for r in ex.map(lambda c: run_case(args, c), order)}
    rows = [rows[c.replace("_", "-")] for c in cases]

    cols = [("case", "case", ""), ("parcels", "parcels", ""), ("fluid_steps", "fluid steps", ""),
            ("solves", "KINSOL solves", ""), ("iterations_mean", "iterations / fluid step", "{:.2f}"),
            ("iterations_max", "most in a step", ""), ("air_steps_mean", "air steps / fluid step", "{:.2f}"),
            ("residual_max_m_s", "largest residual [m/s]", "{:.2e}"),
            ("pressure_iterations_mean", "pressure it. / step", "{:.1f}"),
            ("pressure_unconverged", "unconverged pressure", ""), ("escaped", "escaped parcels", ""),
            ("wall_s", "wall [s]", "{:.0f}"), ("exit_code", "exit", "")]
    with open(os.path.join(args.out, "implicit_all_cases.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([c[0] for c in cols] + ["t_end_s", "digest", "revision", "message"])
        for r in rows:
            w.writerow([r.get(c[0], "") for c in cols] + [r.get(k, "") for k in ("t_end_s", "digest", "revision", "message")])

    def cell(r, key, f):
        v = r.get(key)
        return "—" if v is None else (f.format(v) if f else str(v))

    lines = [f"Implicit drag coupling (KINSOL), every case, t = -0.06 .. {args.end} s, fluid step "
             f"{args.dt_fluid or 'of the case file'}, {args.threads} thread(s), {args.jobs} run(s) at once; "
             f"revision {rows[0].get('revision')}", "",
             "| " + " | ".join(c[1] for c in cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        lines.append("| " + " | ".join(cell(r, c[0], c[2]) for c in cols) + " |")
    failed = [r for r in rows if r["exit_code"] != 0]
    for r in failed:
        lines.append(f"\nCase {r['case']} failed (exit {r['exit_code']}): {r.get('message')}")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "implicit_all_cases.md"), "w") as f:
        f.write(text)
    print(text)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
