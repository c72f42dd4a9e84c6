#!/usr/bin/env python3
"""The infill supply rule over a long run (issue 13).

Runs Block 1 (parameter-files/masada/ratchet-block1.prm) for CYCLES annual
cycles without a supply and with 'Infill supply distance' = the infill
height (2 m: each new fragment is placed as soon as the last has cleared
its place), both at once, and writes supply.csv (the rate per block of 25
cycles, the first fragment's descent, the fragments in the crack and the
static steps) and supply.md (rates with batch-means standard errors).

    python3 supply.py BUILD/rockdda [--cycles 300] [--out DIR]
"""
import argparse
import concurrent.futures
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402
from long_runs import batch_means  # noqa: E402

R = "Ratchet"
SETTINGS = [("no supply", 0.), ("supply 2 m", 2.)]
BLOCK = 25


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=300)
    ap.add_argument("--out", default=here)
    args = ap.parse_args()
    base = open(study.BASE_PRM).read()
    folder, rockdda = study.scratch(args.rockdda, "ratchet-supply-")
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        jobs = [pool.submit(study.run_one, rockdda, folder, f"supply{i}",
                            study.derive_prm(base, {
                                (R, "Cycles"): args.cycles,
                                (R, "Checkpoint cycles"): 0,
                                (R, "Infill supply distance"): d}), 7200)
                for i, (_, d) in enumerate(SETTINGS)]
        runs = [j.result() for j in jobs]
    shutil.rmtree(folder, ignore_errors=True)
    rows, lines = [], [
        "# Infill supply over a long run (Block 1, 4 slices)", "",
        f"{args.cycles} cycles; rates (mm/yr) over blocks of {BLOCK} cycles "
        "and over cycles 101 on, with batch-means standard errors.", "",
        "| setting | rate cycles 31-100 | rate cycles 101- | cumulative (mm) "
        "| fragments | DDA steps | DDA s per century |",
        "|---|---:|---:|---:|---:|---:|---:|"]
    for (label, _), run in zip(SETTINGS, runs):
        if not run["ok"]:
            lines.append(f"| {label} | {run['error']} ||||||")
            continue
        st = run["stats"]
        perm = [1e3 * r["permanent_m"] for r in st]
        for i in range(0, len(st), BLOCK):
            chunk = st[i:i + BLOCK]
            rows.append({
                "setting": label, "cycles": f"{i + 1}-{i + len(chunk)}",
                "rate_mm_per_yr": 1e3 * sum(r["permanent_m"] for r in chunk)
                / len(chunk),
                "infill_descent_m": chunk[-1]["infill_descent_m"],
                "fragments": chunk[-1].get("fragments", 1),
                "steps": sum(r["steps"] for r in chunk)})
        early, early_se = batch_means(perm[30:100], BLOCK)
        late, late_se = batch_means(perm[100:], BLOCK)
        s = run["summary"]
        lines.append(
            f"| {label} | {early:.3f} ± {early_se:.3f} "
            f"| {late:.3f} ± {late_se:.3f} "
            f"| {1e3 * st[-1]['displacement_m']:.1f} "
            f"| {rows[-1]['fragments']:.0f} | {float(s['dda_steps']):.0f} "
            f"| {100 * float(s['dda_seconds']) / len(st):.1f} |")
    with open(os.path.join(args.out, "supply.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "supply.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0 if all(r["ok"] for r in runs) else 1


if __name__ == "__main__":
    sys.exit(main())
