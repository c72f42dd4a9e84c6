#!/usr/bin/python3
"""Cycle jumps of the coupled DDA ratchet: error against cost (issue 13).

usage: jumps.py ROCKDDA [--cycles N] [--tolerance T] [--reference DIR]
                [--only "LABEL;..."] [--repeat R] [--out DIR] [--keep DIR]
                [--suffix X]

Runs the default scene (parameter-files/default.prm: Block 1, 1536 samples
per cycle) for N cycles (default 1000) at the equilibrium tolerance T
(default 1e-8, the default scene's; 1e-9 is the converged setting) once
with every cycle simulated (the reference, label 'full') and with cycle
jumps (Ratchet/Cycle jump, Jump window, Jump tolerance, Jump start;
doc/theory/coupling.md, "Cycle jumps"). With --reference DIR the
reference is read from DIR/statistics.csv and DIR/summary.csv (a full run
of the same scene) instead of run. Each jump setting runs R times (default
1); its wall time is the median, its displacements those of the first run
(a run is deterministic).

For every run: simulated cycles, DDA seconds, wall seconds, and the
cumulative displacement after 100, 200, 500 and N years with its error
against the reference, and the largest of those errors. Writes jumps{X}.csv, jumps{X}.md and jumps{X}.png
(cumulative displacement against years, and error against wall time) into
DIR (default: this script's folder). With --keep DIR the runs are kept in
DIR and a run that completed there before is read, not run again. Exit
status 1 if a run failed.
"""
import argparse
import csv
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402  (derive_prm, run_one, scratch)

R = "Ratchet"


def settings():
    """(label, overrides) of the jump runs."""
    def jump(m, w, tol, start=10):
        return {(R, "Cycle jump"): m, (R, "Jump window"): w,
                (R, "Jump tolerance"): tol, (R, "Jump start"): start}
    return [
        ("jump 256, window 4, tol 0.1", jump(256, 4, 0.1)),
        ("jump 256, window 2, tol 0.1", jump(256, 2, 0.1)),
        ("jump 256, window 4, tol 0.05", jump(256, 4, 0.05)),
        ("jump 64, window 4, tol 0.1", jump(64, 4, 0.1)),
        ("jump 256, window 2, tol 0.1, start 4", jump(256, 2, 0.1, 4)),
    ]


def displacements(stats, years):
    """Cumulative displacement (mm) at the end of each of YEARS."""
    out = []
    for y in years:
        row = next((r for r in stats if int(r["cycle"]) == y), None)
        out.append(1e3 * row["displacement_m"] if row else float("nan"))
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser()
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=1000)
    ap.add_argument("--tolerance", type=float, default=1e-8)
    ap.add_argument("--reference", default="")
    ap.add_argument("--only", default="")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=here)
    ap.add_argument("--keep", default=None)
    ap.add_argument("--suffix", default="")
    args = ap.parse_args()
    base = open(os.path.join(root, "parameter-files", "default.prm")).read()
    common = {(R, "Cycles"): args.cycles,
              (R, "Equilibrium tolerance"): args.tolerance,
              (R, "Checkpoint cycles"): 0}
    folder, rockdda = study.scratch(args.rockdda, "ratchet-jumps-", args.keep)
    years = sorted({y for y in (100, 200, 500, args.cycles)
                    if y <= args.cycles})
    timeout = 6 * 3600
    runs = []
    failed = False
    if args.reference:
        ref = {"label": "full", "ok": True,
               "summary": study.read_summary(
                   os.path.join(args.reference, "summary.csv")),
               "stats": study.read_statistics(
                   os.path.join(args.reference, "statistics.csv"))}
        ref["walls"] = [float(ref["summary"]["wall_time"])]
    else:
        text = study.derive_prm(base, {**common, (R, "Cycle jump"): 0})
        ref = study.run_one(rockdda, folder, "full", text, timeout,
                            reuse=bool(args.keep))
        ref["label"] = "full"
        ref["walls"] = [ref["wall"]]
        if not ref["ok"]:
            sys.exit(f"the reference failed: {ref['error']}")
    runs.append(ref)
    chosen = [(label, over) for label, over in settings()
              if not args.only or label in args.only.split(";")]
    for i, (label, over) in enumerate(chosen):
        text = study.derive_prm(base, {**common, **over})
        walls = []
        first = None
        for rep in range(args.repeat):
            r = study.run_one(rockdda, folder, f"jump{i}-{rep}", text, timeout,
                              reuse=bool(args.keep))
            if not r["ok"]:
                print(f"{label}: failed: {r['error']}", file=sys.stderr)
                failed = True
                break
            walls.append(r["wall"])
            first = first or r
        if first is not None:
            first["label"] = label
            first["walls"] = walls
            runs.append(first)
    ref_d = displacements(ref["stats"], years)
    rows = []
    for r in runs:
        d = displacements(r["stats"], years)
        simulated = sum(1 for s in r["stats"]
                        if s.get("extrapolated", 0.) == 0.)
        rows.append({
            "setting": r["label"],
            "equilibrium_tolerance": args.tolerance,
            "cycles": len(r["stats"]),
            "simulated_cycles": simulated,
            "dda_seconds": float(r["summary"].get("dda_seconds", "nan")),
            "wall_seconds_median": statistics.median(r["walls"]),
            "runs": len(r["walls"]),
            **{f"displacement_{y}_mm": v for y, v in zip(years, d)},
            **{f"error_{y}_percent": 100. * (v - v0) / v0
               for y, v, v0 in zip(years, d, ref_d)},
            "max_error_percent": max(abs(100. * (v - v0) / v0)
                                     for v, v0 in zip(d, ref_d)),
        })
    name = f"jumps{args.suffix}"
    with open(os.path.join(args.out, name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for row in rows:
            w.writerow(row)
    full_wall = rows[0]["wall_seconds_median"]
    with open(os.path.join(args.out, name + ".md"), "w") as f:
        f.write(f"Cycle jumps, default scene, {args.cycles} cycles, "
                f"equilibrium tolerance {args.tolerance:g} "
                f"(`jumps.py`; reference: every cycle simulated)\n\n")
        f.write("| setting | simulated cycles | wall (s) | speed-up | "
                + " | ".join(f"{y} yr (mm, error)" for y in years) + " |\n")
        f.write("|---|---:|---:|---:|" + "---:|" * len(years) + "\n")
        for row in rows:
            cells = []
            for y in years:
                v = row[f"displacement_{y}_mm"]
                e = row[f"error_{y}_percent"]
                cells.append(f"{v:.2f}" if row is rows[0]
                             else f"{v:.2f} ({e:+.1f} %)")
            f.write(f"| {row['setting']} | {row['simulated_cycles']} | "
                    f"{row['wall_seconds_median']:.0f} | "
                    f"{full_wall / row['wall_seconds_median']:.1f}x | "
                    + " | ".join(cells) + " |\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
        for k, r in enumerate(runs):
            t = [s["cycle"] for s in r["stats"]]
            d = [1e3 * s["displacement_m"] for s in r["stats"]]
            a.plot(t, d, "-" if k else "k-", lw=2.5 if k == 0 else 1,
                   label=r["label"])
        a.set_xlabel("years")
        a.set_ylabel("cumulative displacement (mm)")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
        for row in rows[1:]:
            for key, mark in ((f"error_{years[-1]}_percent", "o"),
                              ("max_error_percent", "^")):
                b.plot(row["wall_seconds_median"], abs(row[key]), mark,
                       color="C0" if mark == "o" else "C3")
            b.annotate(row["setting"], (row["wall_seconds_median"],
                                        row["max_error_percent"]),
                       fontsize=6)
        b.axvline(120, color="k", ls=":", lw=1)
        b.set_xlabel("wall time (s); dotted: the 2-minute target")
        b.set_ylabel(f"|error| (%): o after {years[-1]} years, "
                     f"^ largest of {', '.join(map(str, years))}")
        b.grid(True, alpha=0.3)
        b.set_title(f"full run: {full_wall:.0f} s")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, name + ".png"), dpi=110)
    except ImportError:
        print("matplotlib missing: no plot", file=sys.stderr)
    print(open(os.path.join(args.out, name + ".md")).read())
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
