#!/usr/bin/env python3
"""Plot every column of a rockdda statistics.csv against the first column.

usage: plot_statistics.py OUTPUT_DIR [COLUMN ...]
Writes OUTPUT_DIR/statistics.png (one panel per column, units from the
column names, e.g. velocity_m_s -> velocity [m/s]).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

UNITS = ["m_s2", "m_s", "m", "s", "g", "deg", "Pa", "K", "C", "W_m2", "1_m"]


def label(name):
    for u in UNITS:
        if name.endswith("_" + u):
            return f"{name[: -len(u) - 1].replace('_', ' ')} [{u.replace('_', '/')}]"
    return name.replace("_", " ")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    with open(f"{folder}/statistics.csv") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], [[float(v) for v in r] for r in rows[1:] if r]
    wanted = sys.argv[2:] or header[1:]
    cols = [header.index(c) for c in wanted if c in header]
    x = [r[0] for r in data]
    fig, axes = plt.subplots(len(cols), 1, figsize=(9, 1.9 * len(cols) + 0.6),
                             sharex=True, squeeze=False)
    for ax, c in zip(axes[:, 0], cols):
        ax.plot(x, [r[c] for r in data], lw=0.9)
        ax.set_ylabel(label(header[c]), fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel(label(header[0]))
    fig.suptitle(folder, fontsize=9)
    fig.tight_layout()
    fig.savefig(f"{folder}/statistics.png", dpi=100)
    print(f"wrote {folder}/statistics.png")


main()
