#!/usr/bin/python3
"""Long-run convergence of the coupled DDA ratchet of Masada Block 1.

usage: long_runs.py ROCKDDA [--cycles N] [--skip K] [--batch B] [--out DIR]
                    [--samples S] [--only LABEL,...] [--suffix X]
                    [--jobs J] [--replicates R]

The per-cycle permanent displacement of the ratchet is erratic (its
cycle-to-cycle standard deviation is about the rate itself): which contacts
slide first in a warm season decides how far the block goes, and a change
of 1e-9 in any input changes that order (a jammed wedge with friction 0.87
has more than one quasi-static equilibrium; Klarbring 1990). So a rate is
a statistical quantity, and a 5 % convergence statement needs several
hundred cycles per setting. This script runs each setting for N cycles
(default 400), drops the first K (default 50, the infill's first descent),
and gives the rate with its standard error from batch means (batches of B
cycles, default 25, longer than the correlation of successive cycles).
With --replicates R each setting runs R times with the contact penalty
multiplied by 1 + 1e-6 r: the slip sequence changes completely (it changes
at 1e-9 of any input), the process does not, so the replicates are
independent draws and their batches are pooled (the standard error falls
as 1 / sqrt(R)).

Settings: the default (parameter-files/masada/ratchet-block1.prm: 4
slices, 24 steps per cycle, contact penalty 1e13 N/m, automatic pseudo time
step), Slices 2 and 8, Steps per cycle 12 and 48, Contact penalty 4e12 and
2e13 N/m, Pseudo time step 20 s (5x the automatic one). Writes
long-runs.csv and long-runs.md into DIR (default: this script's folder).
Exit status 1 if a run failed.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import shutil
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402  (derive_prm, run_one)

R = "Ratchet"
T = "Thermal forcing"


def settings(samples=0):
    """(label, overrides); SAMPLES > 0 sets the sampling of every run and
    the steps settings bracket it (half, double)."""
    lo, hi = (samples // 2, 2 * samples) if samples > 0 else (12, 48)
    return [
        ("default", {}),
        ("slices 2", {(R, "Slices"): 2}),
        ("slices 8", {(R, "Slices"): 8}),
        (f"steps {lo}", study.sampling(lo)),
        (f"steps {hi}", study.sampling(hi)),
        ("penalty 4e12", {(R, "Contact penalty"): 4e12}),
        ("penalty 2e13", {(R, "Contact penalty"): 2e13}),
        ("pseudo step 20 s", {(R, "Pseudo time step"): 20}),
    ]


def batch_means(x, b):
    """Mean of x and its standard error from means of batches of b."""
    n = len(x) // b
    if n < 2:
        return statistics.fmean(x), float("nan")
    means = [statistics.fmean(x[i * b:(i + 1) * b]) for i in range(n)]
    return statistics.fmean(x), statistics.stdev(means) / math.sqrt(n)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=400)
    ap.add_argument("--skip", type=int, default=50)
    ap.add_argument("--batch", type=int, default=25)
    ap.add_argument("--out", default=here)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--replicates", type=int, default=1,
                    help="runs per setting, the contact penalty multiplied "
                    "by 1 + 1e-6 r (r = 0, 1, ...): independent draws of the "
                    "same process (the slip sequence changes at 1e-9), "
                    "pooled")
    study.add_sampling_argument(ap, note="; the steps settings then "
                                "bracket it")
    ap.add_argument("--only", default="",
                    help="comma-separated setting labels to run (default: "
                    "all)")
    ap.add_argument("--suffix", default="",
                    help="appended to long-runs(.csv/.md)")
    args = ap.parse_args()
    chosen = [(label, {**study.sampling(args.samples), **over})
              for label, over in settings(args.samples)
              if not args.only or label in args.only.split(",")]
    base = open(study.BASE_PRM).read()
    base_penalty = float(re.search(r"set\s+Contact penalty\s*=\s*(\S+)",
                                   base).group(1))
    folder, rockdda = study.scratch(args.rockdda, "ratchet-long-")
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for i, (label, over) in enumerate(chosen):
            for rep in range(args.replicates):
                o = dict(over)
                o[(R, "Cycles")] = args.cycles
                o[(R, "Checkpoint cycles")] = 0
                o[(R, "Contact penalty")] = (
                    o.get((R, "Contact penalty"), base_penalty)
                    * (1. + 1e-6 * rep))
                text = study.derive_prm(base, o)
                jobs[(label, rep)] = pool.submit(
                    study.run_one, rockdda, folder, f"long{i}-{rep}", text,
                    3600)
    rows = []
    failed = False
    for label, _ in chosen:
        runs = [jobs[(label, rep)].result() for rep in range(args.replicates)]
        bad = [r for r in runs if not r["ok"]]
        if bad:
            failed = True
            rows.append({"setting": label, "status": bad[0]["error"]})
            continue
        perm, means = [], []
        for run in runs:
            p = [1e3 * r["permanent_m"] for r in run["stats"]][args.skip:]
            perm += p
            n = len(p) // args.batch
            means += [statistics.fmean(p[k * args.batch:(k + 1) * args.batch])
                      for k in range(n)]
        rate = statistics.fmean(perm)
        se = (statistics.stdev(means) / math.sqrt(len(means))
              if len(means) > 1 else float("nan"))
        stats = [run["stats"] for run in runs]
        s = [run["summary"] for run in runs]
        rows.append({
            "setting": label, "status": "ok", "cycles": len(stats[0]),
            "replicates": len(runs),
            "rate_mm_per_yr": rate, "standard_error": se,
            "std_per_cycle": statistics.stdev(perm),
            "cumulative_mm": statistics.fmean(
                1e3 * st[-1]["displacement_m"] for st in stats),
            "infill_descent_mm": statistics.fmean(
                1e3 * st[-1]["infill_descent_m"] for st in stats),
            "dda_seconds": statistics.fmean(float(x["dda_seconds"])
                                            for x in s),
            "heat_seconds": float(s[0]["heat_seconds"]),
            "pseudo_time_step": float(s[0].get("pseudo_time_step", "nan")),
        })
    shutil.rmtree(folder, ignore_errors=True)
    keys = ["setting", "status", "cycles", "replicates", "rate_mm_per_yr",
            "standard_error",
            "std_per_cycle", "cumulative_mm", "infill_descent_mm",
            "dda_seconds", "heat_seconds", "pseudo_time_step"]
    with open(os.path.join(args.out, f"long-runs{args.suffix}.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    ref = next((r for r in rows if r["setting"] == "default"
                and r["status"] == "ok"), None)
    lines = [
        "# Long runs of the DDA ratchet: rates with standard errors",
        "",
        f"{args.cycles} cycles per setting, "
        + (f"{args.samples} samples per cycle, " if args.samples else "")
        + f"{args.replicates} replicate(s) "
        "(contact penalty x (1 + 1e-6 r)); rate = mean permanent "
        f"displacement per cycle over cycles {args.skip + 1}-{args.cycles} "
        f"(mm/yr), pooled over the replicates; standard error from the batch "
        f"means of {args.batch} cycles of every replicate; cumulative, "
        "descent and DDA seconds are replicate means. "
        "Difference from the default in units of the two rates' combined "
        "standard error.",
        "",
        "| setting | rate (mm/yr) | standard error | std per cycle (mm) "
        "| vs default | difference / s.e. | cumulative (mm) "
        "| infill descent (m) | DDA s | DDA s per century |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        if r["status"] != "ok":
            lines.append(f"| {r['setting']} | {r['status']} |||||||||")
            continue
        d = z = ""
        if ref is not None and r is not ref:
            diff = r["rate_mm_per_yr"] - ref["rate_mm_per_yr"]
            d = f"{100 * diff / ref['rate_mm_per_yr']:+.0f} %"
            z = f"{diff / math.hypot(r['standard_error'], ref['standard_error']):+.1f}"
        lines.append(
            f"| {r['setting']} | {r['rate_mm_per_yr']:.4f} "
            f"| {r['standard_error']:.4f} | {r['std_per_cycle']:.3f} | {d} "
            f"| {z} | {r['cumulative_mm']:.2f} "
            f"| {r['infill_descent_mm'] / 1e3:.2f} | {r['dda_seconds']:.1f} "
            f"| {100 * r['dda_seconds'] / r['cycles']:.1f} |")
    with open(os.path.join(args.out, f"long-runs{args.suffix}.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
