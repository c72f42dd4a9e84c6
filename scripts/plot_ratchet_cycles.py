#!/usr/bin/python3
"""Plot a rockdda 'ratchet' run: OUTPUT_DIR/ratchet.png.

usage: plot_ratchet_cycles.py OUTPUT_DIR

Left: the block's cumulative displacement down the bedding plane against
years (statistics.csv), with the infill's descent. Right: the displacement
within the first and the last recorded cycle against the air temperature
(cycle_loop.csv; the loop of thesis Fig. 5-6).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from rockdda_csv import column, read  # noqa: E402



def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    out = sys.argv[1]
    h, d = read(os.path.join(out, "statistics.csv"))
    years = column(h, d, "time")
    disp = [1e3 * v for v in column(h, d, "displacement")]
    descent = [1e3 * v for v in column(h, d, "infill_descent")]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.plot([0.0] + years, [0.0] + disp, "-", color="C0",
           label="block, down the bedding plane")
    # Cycle jumps (Ratchet/Cycle jump): the simulated cycles as dots.
    if any(name.startswith("extrapolated") for name in h):
        ext = column(h, d, "extrapolated")
        sim = [i for i in range(len(ext)) if ext[i] == 0]
        if len(sim) < len(ext):
            a.plot([years[i] for i in sim], [disp[i] for i in sim], ".",
                   color="C0", ms=4,
                   label="simulated cycles (the rest extrapolated)")
            a.legend(loc="upper left", fontsize=8)
    a.set_xlabel("time (years)")
    a.set_ylabel("cumulative displacement (mm)", color="C0")
    a.grid(True, alpha=0.3)
    if any(abs(v) > 0 for v in descent):
        a2 = a.twinx()
        a2.plot([0.0] + years, [0.0] + descent, "--", color="C1",
                label="infill descent")
        a2.set_ylabel("infill descent (mm)", color="C1")
    a.set_title("ratchet: displacement at the end of each cycle")
    h2, d2 = read(os.path.join(out, "cycle_loop.csv"))
    cyc = column(h2, d2, "cycle")
    air = column(h2, d2, "air_temperature")
    dl = column(h2, d2, "displacement")
    for k, c in enumerate(sorted(set(cyc))):
        xs = [air[i] for i in range(len(cyc)) if cyc[i] == c]
        ys = [1e3 * dl[i] for i in range(len(cyc)) if cyc[i] == c]
        ys0 = ys[0]
        b.plot(xs, [y - ys0 for y in ys], "o-", ms=3, color=f"C{k}",
               label=f"cycle {int(c)}")
        b.plot(xs[0], 0.0, "k+", ms=10)
    b.set_xlabel("air temperature (degC)")
    b.set_ylabel("displacement within the cycle (mm)")
    b.set_title("one cycle (thesis Fig. 5-6 loop); + = start")
    b.grid(True, alpha=0.3)
    b.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "ratchet.png"), dpi=110)


if __name__ == "__main__":
    main()
