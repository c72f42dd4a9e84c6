#!/usr/bin/env python3
"""Stability of 3D DDA at the extremes: run the test Dda3dStability (the
unit test prints one row per case) and write stability.csv and the
Markdown table of the README.

    python3 stability_table.py BUILD_DIR [OUT_DIR]
"""
import csv
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "../../build"
out = sys.argv[2] if len(sys.argv) > 2 else "."
run = subprocess.run(
    [f"{build}/unit-dda3d_stability", "--gtest_filter=Table/Dda3dStability.*"],
    capture_output=True,
    text=True,
)
rows = []
passed = {}
for line in run.stdout.splitlines():
    if line.startswith("stability3d|"):
        f = line.split("|")[1:]
        rows.append(
            dict(
                case=f[0],
                outcome=f[1],
                slide_m=f[2],
                exact_m=f[3],
                error_m=f[4],
                tolerance_m=f[5],
                steps=f[6],
                cuts=f[7],
                wall_s=f[8],
            )
        )
    elif (line.startswith("[       OK ]") or line.startswith("[  FAILED  ]")) \
            and rows and rows[-1]["case"] not in passed:
        # The verdict of the case whose row was printed last.
        passed[rows[-1]["case"]] = line.startswith("[       OK ]")
with open(f"{out}/stability.csv", "w", newline="") as fh:
    w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()) + ["test"])
    w.writeheader()
    for r in rows:
        w.writerow(dict(r, test="pass" if passed.get(r["case"]) else "FAIL"))
print("| case | outcome | slide (m) | exact (m) | error (m) | tolerance (m) "
      "| steps | cuts | wall (s) | test |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(
        f"| {r['case']} | {r['outcome']} | {r['slide_m']} | {r['exact_m']} "
        f"| {r['error_m']} | {r['tolerance_m']} | {r['steps']} | {r['cuts']} "
        f"| {float(r['wall_s']):.3f} | {'pass' if passed.get(r['case']) else 'FAIL'} |"
    )
sys.exit(0 if run.returncode == 0 else 1)
