#!/usr/bin/env python3
"""Quick mode (CI) of the Beverloo discharge: one fill and one discharge of bin_l3.toml.

The half-height fill (72e-9 m^3, a 7 mm bed of 2,600 parcels, settling from t = -0.07 s)
discharges through the b = 2.25 mm (6 d) slot until t = 0.05 s. Its rate over the window
[0.015, 0.05] s must match the Beverloo slot law with the C' and k of the full sweep
(reference.toml, fitted at l = 3 from six slot widths and the full fill) and the bed's own
bulk density, within `tolerance_rate`; and the rate must be steady: the last and first
halves of the window within `tolerance_drift` of each other. Prints both errors.

Usage: check_quick.py CGDEM WORKDIR [CGDEM RUN ARGUMENTS...]   (e.g. --set particles.seed=18, to both runs)
"""
import math
import os
import shutil
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_sweep as sweep  # noqa: E402


def main():
    cgdem, work = sys.argv[1], sys.argv[2]
    with open(os.path.join(sweep.HERE, "reference.toml"), "rb") as f:
        ref = tomllib.load(f)
    q = ref["quick"]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = sweep.case_of(3)
    common = ["--set", f"particles.insert[0].solid_volume={q['solid_volume']}",
              "--set", f"particles.insert[0].max=[12e-3,1.5e-3,{q['insert_top']}]",
              "--set", f"time.start={q['t_start']}", "--set", "output.snapshot_interval=1.0", *sys.argv[3:]]
    fill, dis = os.path.join(work, "fill"), os.path.join(work, "discharge")
    sweep.run(cgdem, [case, "--set", "time.end=0.0", *sweep.slot_sets(0.0), *common], fill, fill + ".log")
    b = q["b"]
    sweep.run(cgdem, [case, "--restart", os.path.join(fill, "settled.bin"), "--set", f"time.end={q['t_end']}",
                      *sweep.slot_sets(b), *common], dis, dis + ".log")
    sweep.WINDOW = (q["window_t0"], q["window_t1"])
    rho_b, phi, top = sweep.bulk_density(fill)
    r = sweep.rate_of(dis)
    d = r["d_m"]
    law = ref["fit_l3"]["C"] * rho_b * math.sqrt(sweep.G) * (b - ref["fit_l3"]["k"] * d) ** 1.5
    err = r["W_per_L_kg_s_m"] / law - 1
    print(f"bed {(top + d / 2 - sweep.FLOOR_TOP) * 1e3:.2f} mm, rho_b {rho_b:.1f} kg/m^3 (phi {phi:.3f}), "
          f"{r['parcels_in_window']} parcels in the window [{q['window_t0']}, {q['window_t1']}] s")
    print(f"[ error ] W/L = {r['W_per_L_kg_s_m']:.5g} +- {r['W_per_L_err_kg_s_m']:.2g} kg/s/m against Beverloo "
          f"(C' = {ref['fit_l3']['C']}, k = {ref['fit_l3']['k']}) {law:.5g} kg/s/m: {err:+.4f} "
          f"(tolerance {q['tolerance_rate']})")
    print(f"[ error ] drift of the rate (last half / first half - 1): {r['drift']:+.4f} "
          f"(tolerance {q['tolerance_drift']})")
    ok = abs(err) <= q["tolerance_rate"] and abs(r["drift"]) <= q["tolerance_drift"]
    print("beverloo quick check passed" if ok else "beverloo quick check FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
