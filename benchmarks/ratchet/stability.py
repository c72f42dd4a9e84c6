#!/usr/bin/python3
"""Long-run stability of the no-infill control of Masada Block 1 (issue 13).

usage: stability.py ROCKDDA [--cycles N] [--creep-cycles M] [--out DIR]
                    [--jobs J]

Two runs of parameter-files/masada/ratchet-block1-no-infill.prm (a clean
crack 20 mm wide, no infill) at the converged penalty 1e13 N/m:

* "below the creep onset": the bedding joint at 0.75 GPa/m, N cycles
  (default 10,000). The joint's elastic range then exceeds the thermal
  displacement of the block's ends, so a rigid-plastic block does not slip
  (Moseley's thermal creep needs slip at both ends): any drift is numerical.
  Bounds: the block's displacement and the crack's aperture stay within
  1 micrometre of their first-cycle values over all N cycles, and the
  stored elastic energy at the end of a cycle (the same phase every cycle)
  does not grow: its change from cycle 1 to cycle N is within 1e-6 of its
  value (the static samples are converged to a motion per step of 1e-9 of
  the block size; an energy change of 1e-6 is 1e3 times that).
* "thesis joint": 1 GPa/m (thesis 5.4.2), M cycles (default 1,000). Above
  the creep onset the block creeps by Moseley's rule (verified in
  tests/unit/test_dda_thermal.cc, BlockOnASlopeCreepsByMoseleysRule): the
  rate must be steady (the two halves' rates within 5 %) and the stored
  energy must not grow (same bound).

Writes stability.csv and stability.md into DIR (default: this folder).
Exit status 1 if a bound is violated or a run fails.
"""
import argparse
import concurrent.futures
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402  (derive_prm, run_one, scratch)

R = "Ratchet"
CONTROL = os.path.join(study.SOURCE, "parameter-files", "masada",
                       "ratchet-block1-no-infill.prm")
YEAR = 31557600.0


def slope(x, y):
    """Least-squares slope of y against x."""
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((a - mx) ** 2 for a in x)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / sxx


def assess(run, kind):
    """Measures and bound checks of one run: (row, failures)."""
    stats = run["stats"]
    cycles = [r["cycle"] for r in stats]
    disp = [r["displacement_m"] for r in stats]
    aper = [r["aperture_m"] for r in stats]
    energy = [r["stored_energy_J_m"] for r in stats]
    n = len(stats)
    row = {
        "run": run["name"],
        "cycles": n,
        "wall_s": run["wall"],
        "cuts": int(sum(r["cuts"] for r in stats)),
        "stationary_samples": int(sum(r["stationary_samples"]
                                      for r in stats)),
        "displacement_drift_m": max(abs(d - disp[0]) for d in disp),
        "aperture_drift_m": max(abs(a - aper[0]) for a in aper),
        "rate_mm_per_yr": slope(cycles, disp) * 1e3,
        "stored_energy_J_per_m": energy[0],
        "energy_change_rel": (energy[-1] - energy[0]) / abs(energy[0]),
        "energy_slope_rel_per_cycle": slope(cycles, energy) / abs(energy[0]),
    }
    half = n // 2
    row["rate_first_half"] = slope(cycles[:half], disp[:half]) * 1e3
    row["rate_second_half"] = slope(cycles[half:], disp[half:]) * 1e3
    fails = []
    if row["energy_change_rel"] > 1e-6:
        fails.append(f"{run['name']}: stored energy grew by "
                     f"{row['energy_change_rel']:.3g} of its value")
    if kind == "stable":
        for key in ("displacement_drift_m", "aperture_drift_m"):
            if row[key] > 1e-6:
                fails.append(f"{run['name']}: {key} {row[key]:.3g} m > 1e-6")
    else:
        a, b = row["rate_first_half"], row["rate_second_half"]
        if not (a > 0 and abs(b - a) <= 0.05 * a):
            fails.append(f"{run['name']}: creep not steady ({a:.4g} then "
                         f"{b:.4g} mm/yr)")
    return row, fails


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=10000)
    ap.add_argument("--creep-cycles", type=int, default=1000)
    ap.add_argument("--out", default=study.HERE)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--keep", default=None,
                    help="run folder to keep (default: a temporary one)")
    args = ap.parse_args()
    folder, rockdda = study.scratch(args.rockdda, "ratchet-stability-",
                                    args.keep)
    text = open(CONTROL).read()
    common = {(R, "Contact penalty"): 1e13, (R, "Checkpoint cycles"): 1000}
    runs = [
        ("below creep onset (0.75 GPa/m)", "stable",
         {**common, (R, "Bedding shear stiffness"): 7.5e8,
          (R, "Cycles"): args.cycles}),
        ("thesis joint (1 GPa/m)", "creep",
         {**common, (R, "Bedding shear stiffness"): 1e9,
          (R, "Cycles"): args.creep_cycles}),
    ]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = [pool.submit(study.run_one, rockdda, folder,
                               f"stability{i}",
                               study.derive_prm(text, over), 24 * 3600)
                   for i, (_, _, over) in enumerate(runs)]
        results = [f.result() for f in futures]
    rows, fails = [], []
    for (label, kind, _), res in zip(runs, results):
        res["name"] = label
        if not res["ok"]:
            fails.append(f"{label}: {res['error']}")
            continue
        row, f = assess(res, kind)
        rows.append(row)
        fails += f
    keys = list(rows[0].keys()) if rows else []
    with open(os.path.join(args.out, "stability.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                        for k, v in r.items()})
    with open(os.path.join(args.out, "stability.md"), "w") as f:
        f.write("# No-infill control: long-run stability (stability.py)\n\n")
        f.write("Clean 20 mm crack, no infill, penalty 1e13 N/m, 24 steps "
                "per cycle. Drifts are the largest change from cycle 1; the "
                "energy is the stored elastic energy at the end of a cycle.\n\n")
        f.write("| run | cycles | wall (s) | cuts | displacement drift (m) | "
                "aperture drift (m) | rate (mm/yr): all / 1st half / 2nd half"
                " | stored energy (J/m) | change, rel. | slope, rel./cycle |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['run']} | {r['cycles']} | {r['wall_s']:.0f} | "
                    f"{r['cuts']} | {r['displacement_drift_m']:.3g} | "
                    f"{r['aperture_drift_m']:.3g} | "
                    f"{r['rate_mm_per_yr']:.4g} / {r['rate_first_half']:.4g}"
                    f" / {r['rate_second_half']:.4g} | "
                    f"{r['stored_energy_J_per_m']:.6g} | "
                    f"{r['energy_change_rel']:.2g} | "
                    f"{r['energy_slope_rel_per_cycle']:.2g} |\n")
        f.write("\nBounds: below the creep onset, both drifts < 1e-6 m; "
                "every run, stored energy change < 1e-6 of its value; the "
                "thesis joint's creep steady within 5 %.\n")
        if fails:
            f.write("\n**Violated:** " + "; ".join(fails) + "\n")
    for line in fails:
        print("stability.py:", line, file=sys.stderr)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
