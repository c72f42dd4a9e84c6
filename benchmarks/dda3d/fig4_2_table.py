#!/usr/bin/env python3
"""Markdown table of a fig4_2_error.py CSV: one row per case, dt and
penalty, one column per strain damping value, each cell the error and, in
brackets, the wall time (s) and the steps.

usage: fig4_2_table.py fig4_2_error.csv
"""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
etas = sorted({r["strain_damping_s"] for r in rows}, key=float)
keys = []
for r in rows:
    k = (r["case"], r["dt_s"], r["penalty_N_per_m"])
    if k not in keys:
        keys.append(k)
cell = {(r["case"], r["dt_s"], r["penalty_N_per_m"], r["strain_damping_s"]): r
        for r in rows}
print("| case | dt (s) | penalty (N/m) | "
      + " | ".join(f"eta = {e} s: error (wall s, steps)" for e in etas) + " |")
print("|---|---|---|" + "---|" * len(etas))
for k in keys:
    out = []
    for e in etas:
        r = cell.get(k + (e,))
        out.append("-" if r is None else
                   f"{float(r['error']):.2e} ({r['wall_s']}, {r['steps']})")
    print(f"| {k[0].upper()} | {k[1]} | {k[2]} | " + " | ".join(out) + " |")
