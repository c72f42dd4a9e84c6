#!/usr/bin/python3
"""Ratchet thresholds of Masada Block 1 by DDA bisection (issue 13).

usage: thresholds.py ROCKDDA [--cycles N] [--iterations K] [--out DIR]
                       [--samples S --suffix X]

Two thresholds of the coupled ratchet (parameter-files/masada/
ratchet-block1.prm), each found by bisection on full DDA runs:

  amplitude  the annual temperature amplitude (K) below which the block
             does not ratchet, searched in [0.5, 9] K;
  friction   the bedding friction angle (deg) above which the block stays
             put although the infill pushes, searched in [41, 70] deg.

A run "ratchets" when its mean permanent displacement per cycle over the
second half of N cycles (default 30) exceeds 1e-3 mm/yr: 2e-4 of the
default rate, and 200 times the drift of the no-infill control (4.9e-6
mm/yr). K bisection steps (default 6) narrow each bracket to 1/64 of it.
Next to each: the analytical threshold of Pasten's model (the same run's
summary.csv, rows ratchet_threshold_*), if the binary writes it.
Writes thresholds.csv and thresholds.md into DIR (default: this folder).
--samples S sets 'Steps per cycle' and 'Thermal forcing/Samples per
cycle' to S (the rate converges in them at about 1536: README, "Steps per
season"); --suffix X names the files thresholdsX.csv / thresholdsX.md.
"""
import argparse
import csv
import os
import shutil
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402

LIMIT = 1e-3  # mm/yr


def rate(run):
    perm = [1e3 * r["permanent_m"] for r in run["stats"]]
    return statistics.fmean(perm[len(perm) // 2:])


def bisect(rockdda, folder, base, key, lo, hi, ratchets_below, cycles,
           iterations, log, extra=None):
    """Bisection of [lo, hi] for the value where the run stops
    ratcheting; ratchets_below: the ratchet runs for values below it."""
    rows = []
    for i in range(iterations):
        mid = 0.5 * (lo + hi)
        text = study.derive_prm(base, {("Ratchet", "Cycles"): cycles,
                                       ("Ratchet", "Checkpoint cycles"): 0,
                                       **(extra or {}), key: mid})
        run = study.run_one(rockdda, folder, f"t{key[1][:4]}{i}", text, 1800)
        if not run["ok"]:
            raise SystemExit(f"thresholds: run at {key[1]} = {mid} failed: "
                             f"{run['error']}")
        r = rate(run)
        moving = r > LIMIT
        rows.append({"key": key[1], "value": mid, "rate_mm_per_yr": r,
                     "ratchets": int(moving),
                     "dda_seconds": float(run["summary"]["dda_seconds"])})
        log(f"  {key[1]} = {mid:.4g}: rate {r:.3g} mm/yr "
            f"({'ratchets' if moving else 'stays'})")
        if moving == ratchets_below:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), 0.5 * (hi - lo), rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=30)
    ap.add_argument("--iterations", type=int, default=6)
    ap.add_argument("--out", default=here)
    study.add_sampling_argument(ap)
    ap.add_argument("--suffix", default="")
    args = ap.parse_args()
    extra = study.sampling(args.samples)
    base = open(study.BASE_PRM).read()
    folder, rockdda = study.scratch(args.rockdda, "ratchet-thresholds-")
    log = lambda s: print(s, flush=True)  # noqa: E731
    log("amplitude threshold (ratchets above it):")
    amp, amp_err, rows_a = bisect(rockdda, folder, base,
                                  ("Thermal forcing", "Annual amplitude"),
                                  0.5, 9., False, args.cycles,
                                  args.iterations, log, extra)
    log("friction threshold (ratchets below it):")
    phi, phi_err, rows_f = bisect(rockdda, folder, base,
                                  ("Ratchet", "Bedding friction angle"),
                                  41., 70., True, args.cycles,
                                  args.iterations, log, extra)
    shutil.rmtree(folder, ignore_errors=True)
    rows = rows_a + rows_f
    with open(os.path.join(args.out, f"thresholds{args.suffix}.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    md = [
        "# Ratchet thresholds of Block 1 by DDA bisection",
        "",
        f"{args.cycles} cycles per run"
        + (f", {args.samples} samples per cycle" if args.samples else "")
        + "; a run ratchets when its mean "
        f"permanent displacement over the second half exceeds {LIMIT} "
        f"mm/yr; {args.iterations} bisection steps.",
        "",
        "| threshold | DDA | bracket half-width |",
        "|---|---:|---:|",
        f"| annual amplitude below which no ratchet (K) | {amp:.3g} "
        f"| {amp_err:.2g} |",
        f"| bedding friction above which the block stays (deg) | {phi:.3g} "
        f"| {phi_err:.2g} |",
        "",
        "| run | value | rate (mm/yr) | ratchets | DDA s |",
        "|---|---:|---:|---|---:|",
    ]
    for r in rows:
        md.append(f"| {r['key']} | {r['value']:.4g} "
                  f"| {r['rate_mm_per_yr']:.3g} "
                  f"| {'yes' if r['ratchets'] else 'no'} "
                  f"| {r['dda_seconds']:.1f} |")
    with open(os.path.join(args.out, f"thresholds{args.suffix}.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    log("\n".join(md))
    return 0


if __name__ == "__main__":
    sys.exit(main())
