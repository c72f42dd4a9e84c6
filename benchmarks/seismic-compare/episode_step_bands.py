#!/usr/bin/env python3
"""Episode slip per event against the step, judged on +-4 % bands of steps.

Reads episode-step-damping.csv (episode_step_damping.sh) and, for each
contact damping ratio, event and nominal step (5, 2.5, 1.25, 0.625 ms)
with its band (0.96, 1 and 1.04 x the step) all run, prints the three
slips, their median and spread, and the sum over the events of the band
medians (a catalogue-like aggregate of the four events).
    python3 benchmarks/seismic-compare/episode_step_bands.py [CSV]
"""
import csv
import os
import statistics
import sys

here = os.path.dirname(os.path.abspath(__file__))
path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    here, "episode-step-damping.csv")
slip = {}
for r in csv.DictReader(open(path)):
    slip[(float(r["zeta"]), int(r["seed"]), round(float(r["dt"]), 7))] = \
        float(r["slip_mm"])
nominal = (0.005, 0.0025, 0.00125, 0.000625)
seeds = (3, 1, 4, 2)
for zeta in sorted({k[0] for k in slip}):
    sums = {}
    print(f"zeta {zeta}")
    for seed in seeds:
        cells = []
        for h in nominal:
            band = [slip.get((zeta, seed, round(f * h, 7)))
                    for f in (0.96, 1., 1.04)]
            if None in band:
                cells.append("-")
                continue
            m = statistics.median(band)
            sums.setdefault(h, []).append(m)
            cells.append(f"{m:.1f} ({', '.join(f'{v:.1f}' for v in band)};"
                         f" spread {100 * (max(band) - min(band)) / m:.0f} %)")
        print(f"  seed {seed}: " + " | ".join(cells))
    print("  sum of band medians: " + " | ".join(
        f"{1e3 * h:g} ms {sum(v):.1f}" for h, v in sums.items()
        if len(v) == len(seeds)))
