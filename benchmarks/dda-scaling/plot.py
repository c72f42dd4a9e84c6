"""Plot the DDA benchmark: per-step time against N (with fitted exponents)
and accuracy against cost of the incline and Newmark cases."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = sys.argv[1] if len(sys.argv) > 1 else "."
rows = list(csv.DictReader(open(f"{here}/scaling.csv")))
acc = list(csv.DictReader(open(f"{here}/accuracy.csv")))

fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
lines = []
for mode in ("static", "dynamic"):
    for solver in ("direct", "cg-block-jacobi", "cg-block-dilu", "cg-block-dilu-2-threads"):
        sel = [r for r in rows if r["mode"] == mode and r["solver"] == solver]
        if not sel:
            continue
        n = [float(r["blocks"]) for r in sel]
        t = [float(r["ms_per_step"]) for r in sel]
        label = f"{mode}, {solver}"
        if len(n) > 1:
            # Least-squares slope of log t against log N.
            x = [math.log(v) for v in n]
            y = [math.log(v) for v in t]
            mx, my = sum(x) / len(x), sum(y) / len(y)
            slope = sum((u - mx) * (v - my) for u, v in zip(x, y)) / sum(
                (u - mx) ** 2 for u in x
            )
            label += f" (N^{slope:.2f})"
            lines.append(f"{mode},{solver},{slope:.3f}")
        a.loglog(n, t, "o-", label=label)
nn = [100, 10000]
a.loglog(nn, [1e3 * v / 1e5 for v in nn], "k--", label="1e5 block-steps/s")
a.set_xlabel("blocks N")
a.set_ylabel("wall time per step (ms)")
a.set_title("DDA brick wall: time per step")
a.legend(fontsize=8)
a.grid(True, which="both", alpha=0.3)
with open(f"{here}/exponents.csv", "w") as f:
    f.write("mode,solver,exponent\n" + "\n".join(lines) + "\n")

markers = {"1e-02": "o", "1e-03": "s", "1e-04": "^"}
for case, colour in (
    ("incline", "C0"),
    ("newmark-inertial", "C1"),
    ("newmark-displacement", "C2"),
):
    for dt, m in markers.items():
        sel = [
            r
            for r in acc
            if r["case"] == case and r["dt_s"] == dt and r["relative_error"] != "nan"
        ]
        if not sel:
            continue
        b.loglog(
            [float(r["penalty_N_per_m"]) for r in sel],
            [max(float(r["relative_error"]), 1e-7) for r in sel],
            m + "-",
            color=colour,
            label=f"{case}, dt={dt} s",
        )
b.axhline(0.01, color="k", ls=":", lw=1)
b.set_xlabel("contact penalty (N/m)  [E = 1e10 Pa]")
b.set_ylabel("relative error")
b.set_title("accuracy vs penalty and time step")
b.legend(fontsize=6, ncol=2)
b.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(f"{here}/dda-scaling.png", dpi=120)
