#!/usr/bin/env python3
"""Quick mode (CI) of the air-impeded discharge (README.md beside this script).

The half fill of the Beverloo bin at l = 3 (2,608 parcels, a 7 mm bed settled in vacuum from
t = -0.07 s) discharges through the b = 2.25 mm slot until t = 0.06 s three times from the
same settled state: in vacuum, with air and the top open, with air and the top sealed. Over
the window [0.03, 0.06] s:
  * the sealed bin's rate must be below `sealed_ratio_max` of the vacuum rate (the displaced
    air has to come in through the slot: it must hold the flow back), and the open bin's
    must lie between the sealed bin's and the vacuum's;
  * each rate with air, as a fraction of the vacuum rate, must match Crewdson et al.'s
    effective gravity (1 + G / (rho_b g))^(1/2), G the measured dp/dz at b/2 above the
    floor, within `tolerance_crewdson` (absolute, in units of the vacuum rate).
Prints every figure and error.

Usage: check_quick.py CGDEM WORKDIR
"""
import math
import os
import shutil
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import run_air  # noqa: E402
from run_air import sweep  # noqa: E402


def main():
    cgdem, work = sys.argv[1], sys.argv[2]
    with open(os.path.join(HERE, "reference.toml"), "rb") as f:
        q = tomllib.load(f)["quick"]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = sweep.case_of(3)
    common = ["--set", f"particles.insert[0].solid_volume={q['solid_volume']}",
              "--set", f"particles.insert[0].max=[12e-3,1.5e-3,{q['insert_top']}]",
              "--set", f"time.start={q['t_start']}"]
    fill = os.path.join(work, "fill")
    sweep.run(cgdem, [case, "--set", "time.end=0.0", "--set", "output.snapshot_interval=1.0", *sweep.slot_sets(0.0),
                      *common], fill, fill + ".log")
    b = q["b"]
    sweep.WINDOW = (q["window_t0"], q["window_t1"])
    rho_b, phi, top = sweep.bulk_density(fill)
    rates, ok = {}, True
    for mode in ["vacuum", "open", "sealed"]:
        d = os.path.join(work, mode)
        sweep.run(cgdem, [case, "--restart", os.path.join(fill, "settled.bin"), "--set", f"time.end={q['t_end']}",
                          "--set", f"output.snapshot_interval={run_air.SNAP}", *sweep.slot_sets(b), *common,
                          *run_air.MODES[mode]], d, d + ".log")
        r = sweep.rate_of(d)
        rates[mode] = r["W_per_L_kg_s_m"]
        if mode == "vacuum":
            print(f"bed {(top + r['d_m'] / 2 - sweep.FLOOR_TOP) * 1e3:.2f} mm, rho_b {rho_b:.1f} kg/m^3; vacuum: "
                  f"W/L = {rates['vacuum']:.5g} +- {r['W_per_L_err_kg_s_m']:.2g} kg/s/m")
            continue
        z, p, n = run_air.pressure_profile(d, b)
        G = run_air.outlet_gradient(z, p, b, 0.5)
        form = math.sqrt(max(1 + G / (rho_b * run_air.G_ACC), 0.0))
        ratio = rates[mode] / rates["vacuum"]
        err = ratio - form
        good = abs(err) <= q["tolerance_crewdson"]
        ok = ok and good
        print(f"[ error ] top {mode}: W/L = {rates[mode]:.5g} +- {r['W_per_L_err_kg_s_m']:.2g} kg/s/m = {ratio:.3f} of "
              f"vacuum; dp/dz at b/2 above the floor {G:.0f} Pa/m ({n} air snapshots) gives "
              f"(1 + G/(rho_b g))^0.5 = {form:.3f}; difference {err:+.3f} (tolerance {q['tolerance_crewdson']})")
    s_ratio = rates["sealed"] / rates["vacuum"]
    order = rates["sealed"] < rates["open"] < rates["vacuum"]
    print(f"[ error ] sealed / vacuum = {s_ratio:.3f} (must be < {q['sealed_ratio_max']}); "
          f"sealed < open < vacuum: {order}")
    ok = ok and s_ratio < q["sealed_ratio_max"] and order
    print("air discharge quick check passed" if ok else "air discharge quick check FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
