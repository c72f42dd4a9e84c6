#!/usr/bin/python3
"""Plot a rockdda 'earthquakes' run: OUTPUT_DIR/earthquakes.png.

usage: plot_earthquakes.py OUTPUT_DIR

Left: displacement of Block 1 per event against magnitude, every seeded
synthetic motion (DDA dots, analytical crosses) with the medians and the
16-84 % spread (events.csv, magnitudes.csv), and the thesis's bounds
(< 42 mm for Mw <= 6.5, > 447 mm for Mw >= 7.0). Right: the largest
distance at which each magnitude still triggers sliding (magnitudes.csv).
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
    he, de = read(os.path.join(out, "events.csv"))
    hm, dm = read(os.path.join(out, "magnitudes.csv"))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    mag = column(he, de, "magnitude")
    left.semilogy([m - 0.04 for m in mag],
                  [max(1e-3 * 1e-3, 1e3 * v) for v in column(he, de, "dda")],
                  "C0.", alpha=0.5, label="DDA, each seed")
    left.semilogy([m + 0.04 for m in mag],
                  [max(1e-3 * 1e-3, 1e3 * v)
                   for v in column(he, de, "analytical")],
                  "C3x", alpha=0.5, label="rigid block, each seed")
    m = column(hm, dm, "magnitude")
    for name, colour, shift in (("dda", "C0", -0.04),
                                ("analytical", "C3", 0.04)):
        med = [1e3 * v for v in column(hm, dm, name + "_median")]
        lo = [1e3 * v for v in column(hm, dm, name + "_p16")]
        hi = [1e3 * v for v in column(hm, dm, name + "_p84")]
        left.errorbar([x + shift for x in m], med,
                      yerr=[[a - b for a, b in zip(med, lo)],
                            [b - a for a, b in zip(med, hi)]],
                      fmt="o", color=colour, capsize=3,
                      label=f"{name} median, 16-84 %")
    left.plot([5.9, 6.6], [42, 42], "k--", lw=1)
    left.plot([6.9, 7.6], [447, 447], "k:", lw=1)
    left.text(5.9, 50, "thesis: < 42 mm", fontsize=8)
    left.text(6.9, 520, "thesis: > 447 mm", fontsize=8)
    left.set_xlabel("moment magnitude Mw")
    left.set_ylabel("displacement per event (mm)")
    left.legend(fontsize=7, loc="lower right")
    right.plot(m, [1e-3 * v for v in column(hm, dm, "trigger_distance")],
               "ko-")
    right.set_xlabel("moment magnitude Mw")
    right.set_ylabel("largest distance that triggers sliding (km)")
    right.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "earthquakes.png"), dpi=120)


if __name__ == "__main__":
    main()
