#!/usr/bin/python3
"""The ratchet's sensitivity at the converged sampling (issue 13).

usage: sensitivity_1536.py ROCKDDA [--cycles N] [--samples S] [--out DIR]

Runs parameter-files/masada/ratchet-block1.prm with 'Steps per cycle' =
'Thermal forcing/Samples per cycle' = S (default 1536, where the rate
converges: README, "Steps per season") for N cycles (default 20): the
base and one change at a time (slope 15 and 25 deg, a crack of half the
width, amplitude 15 K). Prints and writes sensitivity-1536.csv into DIR
(default: this folder): the DDA rate over the second half of the cycles and
Pasten's rates from the same run's summary.csv. About 1 minute per run.
"""
import argparse
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402

CASES = [("base", {}),
         ("slope 15 deg", {("Ratchet", "Slope"): 15}),
         ("slope 25 deg", {("Ratchet", "Slope"): 25}),
         ("crack 0.1 / 0.01 m", {("Ratchet", "Crack top width"): 0.1,
                                 ("Ratchet", "Crack bottom width"): 0.01}),
         ("amplitude 15 K", {("Thermal forcing", "Annual amplitude"): 15})]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=20)
    study.add_sampling_argument(ap, default=1536)
    ap.add_argument("--out", default=here)
    args = ap.parse_args()
    base = open(study.BASE_PRM).read()
    folder, rockdda = study.scratch(args.rockdda, "ratchet-sensitivity-")
    rows = []
    try:
        for k, (name, change) in enumerate(CASES):
            text = study.derive_prm(base, {("Ratchet", "Cycles"): args.cycles,
                                           ("Ratchet", "Checkpoint cycles"): 0,
                                           **study.sampling(args.samples),
                                           **change})
            run = study.run_one(rockdda, folder, f"run{k}", text, 7200)
            if not run["ok"]:
                sys.stderr.write(f"{name}: {run['error']}\n")
                return 1
            summ = run["summary"]
            row = {"case": name,
                   "dda_rate_mm_per_yr":
                       f"{study.measures(run)['rate']:.4f}",
                   "pasten_045_mm_per_yr":
                       f"{float(summ['analytical_rate_beta_0.45']):.3f}",
                   "pasten_07_mm_per_yr":
                       f"{float(summ['analytical_rate_beta_0.7']):.3f}",
                   "dda_seconds": f"{float(summ['dda_seconds']):.1f}"}
            print(row, flush=True)
            rows.append(row)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    with open(os.path.join(args.out, "sensitivity-1536.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
