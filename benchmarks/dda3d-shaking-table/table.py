#!/usr/bin/env python3
"""Markdown table of shaking_table.py CSVs: one row per normal penalty and
dt, one column per file and mode; each cell the history error, the onset
(s) and steps / cuts, or the time at which the run stopped.

usage: table.py LABEL=FILE.csv [LABEL=FILE.csv ...]
"""
import csv
import re
import sys

cols, cells, keys = [], {}, []
for arg in sys.argv[1:]:
    label, path = arg.split("=", 1)
    for r in csv.DictReader(open(path)):
        if r["mode"] == "analytical":
            continue
        col = f"{r['mode']}, {label}"
        if col not in cols:
            cols.append(col)
        key = (r["penalty_N_per_m"], r["dt_s"])
        if key not in keys:
            keys.append(key)
        if r["status"] == "ok":
            text = (f"{100 * float(r['error_history']):.2f} %, {r['onset_s']}, "
                    f"{r['steps']} / {r['cuts']}")
        else:
            m = re.search(r"at t = ([0-9.]+) s", r["status"])
            text = f"stops at {float(m.group(1)):.1f} s" if m else "failed"
        cells[(key, col)] = text
order = list(cols)
cols.sort(key=lambda c: (not c.startswith("loading"), order.index(c)))
print("| penalty (N/m), dt (s) | " + " | ".join(cols) + " |")
print("|---|" + "---|" * len(cols))
for k in keys:
    print(f"| {k[0]}, {k[1]} | "
          + " | ".join(cells.get((k, c), "-") for c in cols) + " |")
