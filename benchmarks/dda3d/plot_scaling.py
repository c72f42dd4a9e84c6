"""Plot the 3D DDA scaling benchmark: wall time per step against N (static
and dynamic) with the fitted exponent of time against N (least squares of
log t on log N), and block-steps per second; writes scaling.png and
exponents.csv. Rows of scaling-10k-single.csv (if present: single runs,
no median, too slow to repeat) are drawn as open markers, and the
exponent of their mode is fitted once more with them. The rows of
scaling-before-c9fa5a6.csv and scaling-before-c9fa5a6-10k-single.csv (if
present: the engine before the block-sparse CG, sparse LDL^T at every
open-close iteration) are drawn dashed, for comparison.

    python3 plot_scaling.py DIR   (DIR holds scaling.csv)
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = sys.argv[1] if len(sys.argv) > 1 else "."
rows = list(csv.DictReader(open(f"{here}/scaling.csv")))



def read(name):
    try:
        return list(csv.DictReader(open(f"{here}/{name}")))
    except FileNotFoundError:
        return []


single = read("scaling-10k-single.csv")
before = read("scaling-before-c9fa5a6.csv") + read(
    "scaling-before-c9fa5a6-10k-single.csv"
)


def exponent(n, t):
    x = [math.log(v) for v in n]
    y = [math.log(v) for v in t]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return sum((u - mx) * (v - my) for u, v in zip(x, y)) / sum(
        (u - mx) ** 2 for u in x
    )


fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
lines = []
for mode, colour in (("static", "C0"), ("dynamic", "C1")):
    sel = [r for r in rows if r["mode"] == mode]
    if not sel:
        continue
    n = [float(r["blocks"]) for r in sel]
    t = [float(r["ms_per_step"]) for r in sel]
    label = mode
    if len(n) > 1:
        slope = exponent(n, t)
        label += f" (t ~ N^{slope:.2f})"
        lines.append(f"{mode},median,{len(n)},{int(min(n))},{int(max(n))},{slope:.3f}")
    a.loglog(n, t, "o-", color=colour, label=label)
    b.semilogx(
        n, [float(r["block_steps_per_s"]) for r in sel], "o-", color=colour, label=mode
    )
    old = [r for r in before if r["mode"] == mode]
    if old:
        a.loglog([float(r["blocks"]) for r in old],
                 [float(r["ms_per_step"]) for r in old], "s--", mfc="none",
                 color=colour, alpha=0.6, label=f"{mode}, before (c9fa5a6, LDL^T)")
        b.semilogx([float(r["blocks"]) for r in old],
                   [float(r["block_steps_per_s"]) for r in old], "s--",
                   mfc="none", color=colour, alpha=0.6)
    one = [r for r in single if r["mode"] == mode]
    if one:
        n1 = [float(r["blocks"]) for r in one]
        t1 = [float(r["ms_per_step"]) for r in one]
        slope = exponent(n + n1, t + t1)
        lines.append(
            f"{mode},with-single-run,{len(n) + len(n1)},{int(min(n + n1))},"
            f"{int(max(n + n1))},{slope:.3f}"
        )
        a.loglog(n1, t1, "o", mfc="none", color=colour,
                 label=f"{mode}, 1 step, no median (all: N^{slope:.2f})")
        b.semilogx(n1, [float(r["block_steps_per_s"]) for r in one], "o",
                   mfc="none", color=colour)
a.set_xlabel("blocks N")
a.set_ylabel("wall time per step (ms)")
a.set_title("3D DDA running-bond wall: time per step")
a.legend()
a.grid(True, which="both", alpha=0.3)
b.set_xlabel("blocks N")
b.set_ylabel("block-steps per second")
b.set_title("3D DDA throughput (median of 3 runs)")
b.legend()
b.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(f"{here}/scaling.png", dpi=110)
with open(f"{here}/exponents.csv", "w") as f:
    f.write("mode,data,points,n_min,n_max,exponent\n" + "\n".join(lines) + "\n")
print("\n".join(lines))
