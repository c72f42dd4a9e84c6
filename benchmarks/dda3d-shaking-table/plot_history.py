#!/usr/bin/env python3
"""Plot the shaking-table wedge's slide (along the line of intersection)
against time: the analytical rigid wedge (sliding3d) and the DDA runs kept
by shaking_table.py --histories DIR.

usage: plot_history.py DIR OUT.png RUN [RUN ...]
       (RUN: MODE-DT-PENALTY[-OPTIONS], as shaking_table.py names them)
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        r = list(csv.reader(f))
    return [dict(zip(r[0], map(float, x))) for x in r[1:]]


def main():
    folder, out, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
    an = rows(os.path.join(folder, "analytical.csv"))
    end = [an[-1][f"displacement_{c}_m"] for c in "xyz"]
    line = [x / math.hypot(*end) for x in end]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot([r["time_s"] for r in an],
            [sum(r[f"displacement_{c}_m"] * l for c, l in zip("xyz", line))
             for r in an], "k-", lw=2.5, label="analytical (sliding3d)")
    for run in runs:
        h = rows(os.path.join(folder, run + ".csv"))
        mode, dt, pen = run.split("-", 2)
        pen, _, options = pen.partition("-")
        opts = options.split("-")
        extra = ", stiff-mode velocity" if "sv" in opts else ""
        ks = [o[2:] for o in opts if o.startswith("ks")]
        extra += (f", shear {float(ks[0]):.0e} N/m" if ks
                  else ", shear 0.4 p")
        ax.plot([r["time_s"] for r in h],
                [sum((r[f"mp1_u{c}_m"] - r.get(f"ground_u{c}_m", 0.)) * l
                     for c, l in zip("xyz", line)) for r in h],
                "--" if mode == "displacement" else "-", lw=1.2,
                label=f"3D DDA, {mode} mode, p = {float(pen):.0e} N/m, "
                      f"dt = {dt} s{extra}")
    ax.set_xlabel("time (s; the record starts after 1.2 s of filter padding)")
    ax.set_ylabel("slide along the line of intersection (m)")
    ax.set_title("Shaking-table wedge 51.4/065.8, 51.4/295.2: 2 Hz, 0.21 g, "
                 "5 s ramp, 2.5 Hz low-pass")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main()
