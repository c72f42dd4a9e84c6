#!/usr/bin/python3
"""Plot cutting time against segment count and fit the growth exponent."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(here, "results.csv"))))
n = [float(r["segments"]) for r in rows]
t = [float(r["cut_s"]) for r in rows]
b = [float(r["blocks"]) for r in rows]
# Least-squares slope of log t against log n over the runs with n >= 1e4.
pts = [(math.log(x), math.log(y)) for x, y in zip(n, t) if x >= 9e3]
if len(pts) >= 2:
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    slope = (sum((p[0] - mx) * (p[1] - my) for p in pts)
             / sum((p[0] - mx) ** 2 for p in pts))
else:
    slope = float("nan")
with open(os.path.join(here, "results.md"), "w") as f:
    f.write("| segments | blocks | cut time (s) | time per segment (us) |\n")
    f.write("|---:|---:|---:|---:|\n")
    for x, y, z in zip(n, t, b):
        f.write(f"| {int(x)} | {int(z)} | {y:.3f} | {1e6 * y / x:.1f} |\n")
    f.write(f"\nFitted growth (n >= 1e4): time ~ n^{slope:.2f}\n")
fig, ax = plt.subplots(figsize=(6, 4.5))
ax.loglog(n, t, "o-", label=f"exact cutting (growth n^{slope:.2f})")
ref = [t[0] * x / n[0] for x in n]
ax.loglog(n, ref, "k--", lw=0.8, label="linear reference")
ax.axhline(10, color="r", lw=0.8, ls=":", label="target: 100k in 10 s")
ax.set_xlabel("segments")
ax.set_ylabel("cut time (s)")
ax.set_title("CGAL exact arrangement block cutting")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(here, "cutting_time.png"), dpi=120)
