#!/usr/bin/python3
"""Plot of a 'calibrate' run (thesis Fig. 5-16): Eq. 5.10 error against the
penalty, one line per time step and one panel per frequency, and the wall
time of each run against its error.

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


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "."
    header, rows = rockdda_csv.read(os.path.join(folder, "calibration.csv"))
    col = {name: rockdda_csv.column(header, rows, name)
           for name in ("frequency", "penalty", "time_step", "error",
                        "wall_time")}
    freqs = sorted(set(col["frequency"]))
    steps = sorted(set(col["time_step"]), reverse=True)
    fig, axes = plt.subplots(1, len(freqs) + 1,
                             figsize=(4.5 * (len(freqs) + 1), 4))
    markers = "osd^v<>"
    for ax, f in zip(axes, freqs):
        for j, dt in enumerate(steps):
            pts = sorted((k, e) for fr, k, s, e in zip(
                col["frequency"], col["penalty"], col["time_step"],
                col["error"]) if fr == f and s == dt and math.isfinite(e))
            if pts:
                ax.plot([p[0] / 1e9 for p in pts],
                        [max(p[1], 1e-3) for p in pts],
                        marker=markers[j % len(markers)],
                        label=f"dt = {dt:g} s")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("contact penalty k (GN/m)")
        ax.set_ylabel("relative error R_e (%)")
        ax.set_title(f"{f:g} Hz")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    ax = axes[-1]
    for j, dt in enumerate(steps):
        pts = [(w, e) for s, w, e in zip(col["time_step"], col["wall_time"],
                                         col["error"])
               if s == dt and math.isfinite(e)]
        ax.scatter([p[0] for p in pts], [max(p[1], 1e-3) for p in pts],
                   marker=markers[j % len(markers)], label=f"dt = {dt:g} s")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run (s)")
    ax.set_ylabel("relative error R_e (%)")
    ax.set_title("speed against accuracy")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "calibration.png"), dpi=120)


if __name__ == "__main__":
    main()
