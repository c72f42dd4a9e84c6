#!/usr/bin/python3
"""Plot a rockdda 'record' run: OUTPUT_DIR/record.png.

usage: plot_record.py OUTPUT_DIR

Acceleration, velocity and displacement against time, the Fourier
amplitude spectrum and the response spectrum (pseudo-acceleration), each
before (unprocessed.csv, with the same scaling) and after processing
(statistics.csv, fourier.csv, response_spectrum.csv).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    data = [[float(v) for v in r] for r in rows[1:] if r]
    return {name: [r[i] for r in data] for i, name in enumerate(header)}


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    out = sys.argv[1]
    p = read(os.path.join(out, "statistics.csv"))
    u = read(os.path.join(out, "unprocessed.csv"))
    f = read(os.path.join(out, "fourier.csv"))
    r = read(os.path.join(out, "response_spectrum.csv"))
    fig = plt.figure(figsize=(12, 9))
    grid = fig.add_gridspec(3, 2)
    series = [("acceleration_g", "acceleration (g)", 1.0),
              ("velocity_m_s", "velocity (cm/s)", 100.0),
              ("displacement_m", "displacement (cm)", 100.0)]
    for row, (key, label, factor) in enumerate(series):
        ax = fig.add_subplot(grid[row, 0])
        ax.plot(u["time_s"], [factor * v for v in u[key]], color="0.6",
                lw=0.8, label="unprocessed")
        ax.plot(p["time_s"], [factor * v for v in p[key]], color="C0",
                lw=0.8, label="processed")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        if row == 0:
            ax.legend(loc="upper right", fontsize=8)
        if row == 2:
            ax.set_xlabel("time (s)")
    ax = fig.add_subplot(grid[0, 1])
    freq = f["frequency_Hz"][1:]
    ax.loglog(freq, f["amplitude_unprocessed_g*s"][1:], color="0.6", lw=0.7,
              label="unprocessed")
    ax.loglog(freq, f["amplitude_g*s"][1:], color="C0", lw=0.7,
              label="processed")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("Fourier amplitude (g s)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    positive = [a for a in f["amplitude_g*s"][1:] if a > 0]
    if positive:
        ax.set_ylim(bottom=max(min(positive), 1e-6 * max(positive)))
    ax = fig.add_subplot(grid[1:, 1])
    ax.semilogx(r["period_s"], r["pseudo_acceleration_unprocessed_g"],
                color="0.6", label="unprocessed")
    ax.semilogx(r["period_s"], r["pseudo_acceleration_g"], color="C0",
                label="processed")
    ax.set_xlabel("period (s)")
    ax.set_ylabel("pseudo-acceleration (g)")
    ax.set_title("response spectrum", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(os.path.basename(os.path.normpath(out)))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "record.png"), dpi=110)


if __name__ == "__main__":
    main()
