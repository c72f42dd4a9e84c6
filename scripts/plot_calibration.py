#!/usr/bin/python3
"""Plot of a 'calibrate' run (thesis Fig. 5-16): Eq. 5.10 error against the
penalty, one line per time step and one panel per input (sinusoid frequency
or record polarity) and loading mode, and the wall time of each run against
its error.

usage: plot_calibration.py OUTPUT_DIR   (reads calibration.csv, writes
calibration.png)
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rockdda_csv  # noqa: E402

MODES = {0.: "loading", 1.: "displacement"}


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "."
    header, rows = rockdda_csv.read(os.path.join(folder, "calibration.csv"))
    col = {name: rockdda_csv.column(header, rows, name)
           for name in ("frequency", "penalty", "time_step", "error",
                        "wall_time", "mode", "polarity")}
    runs = [dict(zip(col, values)) for values in zip(*col.values())]
    # One panel per input (frequency, polarity) and mode, in file order.
    groups = []
    for r in runs:
        g = (r["mode"], r["frequency"], r["polarity"])
        if g not in groups:
            groups.append(g)
    modes = sorted({g[0] for g in groups})
    polarities = sorted({g[2] for g in groups})

    def title(g):
        mode, f, pol = g
        t = f"{f:g} Hz" if f > 0 else "record"
        if len(polarities) > 1:
            t += ", inverted" if pol < 0 else ", normal"
        if len(modes) > 1:
            t += f", {MODES.get(mode, mode)} mode"
        return t

    steps = sorted({r["time_step"] for r in runs}, reverse=True)
    fig, axes = plt.subplots(1, len(groups) + 1,
                             figsize=(4.5 * (len(groups) + 1), 4))
    markers = "osd^v<>"
    for ax, g in zip(axes, groups):
        for j, dt in enumerate(steps):
            pts = sorted((r["penalty"], r["error"]) for r in runs
                         if (r["mode"], r["frequency"], r["polarity"]) == g
                         and r["time_step"] == dt and math.isfinite(r["error"]))
            if pts:
                ax.plot([p[0] / 1e9 for p in pts],
                        [max(p[1], 1e-3) for p in pts],
                        marker=markers[j % len(markers)],
                        label=f"dt = {dt:g} s")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("contact penalty k (GN/m)")
        ax.set_ylabel("relative error R_e (%)")
        ax.set_title(title(g))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    ax = axes[-1]
    for m, mode in enumerate(modes):
        for j, dt in enumerate(steps):
            pts = [(r["wall_time"], r["error"]) for r in runs
                   if r["time_step"] == dt and r["mode"] == mode
                   and math.isfinite(r["error"])]
            label = f"dt = {dt:g} s"
            if len(modes) > 1:
                label += f", {MODES.get(mode, mode)}"
            # The second mode in open markers.
            style = ({"color": f"C{j}"} if m == 0 else
                     {"facecolors": "none", "edgecolors": f"C{j}"})
            ax.scatter([p[0] for p in pts], [max(p[1], 1e-3) for p in pts],
                       marker=markers[j % len(markers)], label=label, **style)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run (s)")
    ax.set_ylabel("relative error R_e (%)")
    ax.set_title("speed against accuracy")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "calibration.png"), dpi=120)


if __name__ == "__main__":
    main()
