#!/usr/bin/env python3
"""Quick mode (CI) of the fill ratio against shoe speed (README.md beside this script).

shoe_slab_quick.toml (a 3.6 mm long, 3 mm deep die under a 3.6 mm shoe cavity, a 2.4 mm slab,
688 parcels at l = 3) through run_sweep.py: one settle and one fill at rest (M_full) in
vacuum, then passes at the slow and the fast speed of reference.toml in vacuum and one slow
pass with air. Asserts, with every figure printed:
  * the slow pass in vacuum fills the die (delta >= delta_full_min);
  * the fast pass in vacuum under-fills it (delta <= delta_fast_max);
  * with air the slow pass brings less powder (delta_vacuum - delta_air >= air_deficit_min).
Usage: check_quick.py CGDEM WORKDIR
"""
import os
import shutil
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import run_sweep  # noqa: E402


def main():
    cgdem, work = sys.argv[1], sys.argv[2]
    with open(os.path.join(HERE, "reference.toml"), "rb") as f:
        q = tomllib.load(f)["quick"]
    shutil.rmtree(work, ignore_errors=True)
    run_sweep.CASE = os.path.join(HERE, "shoe_slab_quick.toml")
    slow, fast = q["slow"], q["fast"]
    run_sweep.run_all(cgdem, work, [(run_sweep.D_REF, 3.0)], [slow], ["vacuum", "air"], 1)
    run_sweep.run_all(cgdem, work, [(run_sweep.D_REF, 3.0)], [fast], ["vacuum"], 1)
    df, _ = run_sweep.analyse(work, [(run_sweep.D_REF, 3.0)], [slow, fast])
    d = {(r["mode"], r["v_m_s"]): r["delta"] for _, r in df.iterrows()}
    checks = [
        (f"slow pass ({slow} m/s) in vacuum fills the die: delta = {d['vacuum', slow]:.3f} >= {q['delta_full_min']}",
         d["vacuum", slow] >= q["delta_full_min"]),
        (f"fast pass ({fast} m/s) in vacuum under-fills it: delta = {d['vacuum', fast]:.3f} <= {q['delta_fast_max']}",
         d["vacuum", fast] <= q["delta_fast_max"]),
        (f"air holds powder back at {slow} m/s: delta vacuum - air = {d['vacuum', slow]:.3f} - {d['air', slow]:.3f} = "
         f"{d['vacuum', slow] - d['air', slow]:.3f} >= {q['air_deficit_min']}",
         d["vacuum", slow] - d["air", slow] >= q["air_deficit_min"]),
    ]
    ok = True
    for text, passed in checks:
        print(("PASS " if passed else "FAIL ") + text)
        ok &= passed
    if not ok:
        sys.exit("fill ratio quick check failed")
    print("fill ratio quick check passed")


if __name__ == "__main__":
    main()
