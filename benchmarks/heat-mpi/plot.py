"""Tabulate and plot the heat MPI benchmark (timings.csv -> results.md,
timings.png): medians of the repeats, speed-up against the serial solver
measured in the same run, and the largest probe difference to it."""
import csv
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = sys.argv[1] if len(sys.argv) > 1 else "."
rows = list(csv.DictReader(open(f"{here}/timings.csv")))
groups = defaultdict(list)
for r in rows:
    groups[(int(r["refinements"]), r["config"])].append(r)

configs = ["serial", "mpi-1", "mpi-2"]
labels = {"serial": "1 process, serial solver (CG + SSOR)",
          "mpi-1": "mpirun -np 1, distributed (CG + AMG)",
          "mpi-2": "mpirun -np 2, distributed (CG + AMG)"}
levels = sorted({k[0] for k in groups})
lines = ["| cells | dofs | configuration | wall time (s, median of 3) | "
         "speed-up vs serial | peak memory per process (MB) | "
         "max probe difference to serial (K) |",
         "|---:|---:|---|---:|---:|---:|---:|"]
curves = defaultdict(list)
for level in levels:
    base = groups.get((level, "serial"))
    t_base = statistics.median(float(r["wall_time_s"]) for r in base) if base else None
    for c in configs:
        g = groups.get((level, c))
        if not g:
            continue
        t = statistics.median(float(r["wall_time_s"]) for r in g)
        mem = statistics.median(float(r["max_rss_mb"]) for r in g)
        diff = 0.0
        if base:
            for k in ("final_probe1", "final_probe2", "final_block1_mean"):
                diff = max(diff, abs(float(g[0][k]) - float(base[0][k])))
        cells = int(g[0]["cells"])
        curves[c].append((cells, t))
        lines.append(f"| {cells:,} | {int(g[0]['dofs']):,} | {labels[c]} | {t:.2f} | "
                     f"{t_base / t:.2f} | {mem:.0f} | {diff:.1e} |")
open(f"{here}/results.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))

fig, ax = plt.subplots(figsize=(6.5, 4.5))
for c in configs:
    pts = sorted(curves[c])
    if pts:
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=labels[c])
ax.set_xlabel("cells")
ax.set_ylabel("wall time of 24 hourly steps (s)")
ax.set_title("Heat, Masada Block 1 size, FE_Q(1), Crank-Nicolson")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(f"{here}/timings.png", dpi=120)
