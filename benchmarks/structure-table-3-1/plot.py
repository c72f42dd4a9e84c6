#!/usr/bin/python3
"""Table 3-1 study: table of block counts and widths, and plots of block
count against b (per L) and mean width against b/L (thesis Fig. 3-6)."""
import csv
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(here, "results.csv"))))
models = {}
for r in rows:
    models.setdefault(r["model"], []).append(r)


def mean(rs, key):
    return statistics.mean(float(r[key]) for r in rs)


def sd(rs, key):
    return statistics.stdev(float(r[key]) for r in rs) if len(rs) > 1 else 0.0


order = ["FMML"] + [str(i) for i in range(1, 16)]
with open(os.path.join(here, "results.md"), "w") as f:
    n_seeds = len(models["FMML"])
    f.write(f"Mean (and standard deviation) over {n_seeds} seeds.\n\n")
    f.write("| model | L (m) | b (m) | b/L | blocks | mean width (m) "
            "| mean area (m^2) | P21 joints (1/m) |\n")
    f.write("|---|---:|---:|---:|---:|---:|---:|---:|\n")
    for m in order:
        rs = models[m]
        L = float(rs[0]["L_m"]) if m != "FMML" else None
        b = float(rs[0]["b_m"]) if m != "FMML" else None
        f.write(
            f"| {m} | {'-' if L is None else int(L)} | "
            f"{'-' if b is None else int(b)} | "
            f"{'-' if L is None else f'{b / L:.1f}'} | "
            f"{mean(rs, 'blocks'):.0f} ({sd(rs, 'blocks'):.0f}) | "
            f"{mean(rs, 'mean_width_m'):.3f} ({sd(rs, 'mean_width_m'):.3f}) | "
            f"{mean(rs, 'mean_area_m2'):.3f} | "
            f"{mean(rs, 'p21_joints_per_m'):.3f} |\n")

fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
for L, marker in ((5, "o"), (10, "s"), (15, "^")):
    ms = [str(i) for i in range(1, 16) if float(models[str(i)][0]["L_m"]) == L]
    bs = [float(models[m][0]["b_m"]) for m in ms]
    a1.errorbar(bs, [mean(models[m], "blocks") for m in ms],
                yerr=[sd(models[m], "blocks") for m in ms],
                marker=marker, capsize=3, label=f"DL, L = {L} m")
    a2.errorbar([b / L for b in bs],
                [mean(models[m], "mean_width_m") for m in ms],
                yerr=[sd(models[m], "mean_width_m") for m in ms],
                marker=marker, ls="none", capsize=3, label=f"DL, L = {L} m")
a1.axhline(mean(models["FMML"], "blocks"), color="k", ls="--",
           label="layered (FMML, FSI = 1.3)")
a2.axhline(mean(models["FMML"], "mean_width_m"), color="k", ls="--",
           label="layered (FMML)")
a1.set_xlabel("mean rock bridge b (m)")
a1.set_ylabel("number of blocks")
a1.set_title("Block count (thesis Table 3-1 models)")
a1.legend(fontsize=8)
a2.set_xlabel("b / L")
a2.set_ylabel("mean block width along bedding (m)")
a2.set_title("Mean block width vs b/L (cf. thesis Fig. 3-6)")
a2.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(here, "table_3_1.png"), dpi=120)
