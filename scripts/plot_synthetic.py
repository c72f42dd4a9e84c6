#!/usr/bin/python3
"""Plot a rockdda 'synthetic-motion' run: OUTPUT_DIR/synthetic.png.

usage: plot_synthetic.py OUTPUT_DIR

Top: the first realisation's acceleration (record-0001.csv, if written).
Bottom left: PGA of every realisation on rock (and with the site, if any)
against the BJF97 median and its +-1 sigma band (statistics.csv). Bottom
right: the quadratic mean of the realisations' Fourier amplitude spectra
against the target, in 1/6-octave bands (fourier.csv), and the site
amplification on a second axis.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from rockdda_csv import column, read  # noqa: E402

SIGMA_LN_BJF97 = 0.495



def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    out = sys.argv[1]
    fig = plt.figure(figsize=(11, 7.5))
    top = fig.add_subplot(2, 1, 1)
    left = fig.add_subplot(2, 2, 3)
    right = fig.add_subplot(2, 2, 4)

    rec = os.path.join(out, "record-0001.csv")
    if os.path.exists(rec):
        h, d = read(rec)
        top.plot(column(h, d, "time"), column(h, d, "acceleration"), lw=0.6)
        top.set_title("realisation 1")
    else:
        top.text(0.5, 0.5, "records not written", ha="center",
                 transform=top.transAxes)
    top.set_xlabel("time (s)")
    top.set_ylabel("acceleration (g)")
    top.grid(True, alpha=0.3)

    h, d = read(os.path.join(out, "statistics.csv"))
    n = column(h, d, "realisation")
    pga = column(h, d, "pga")
    rock = column(h, d, "pga_rock")
    bjf = column(h, d, "bjf97_median")[0]
    left.axhspan(bjf * math.exp(-SIGMA_LN_BJF97),
                 bjf * math.exp(SIGMA_LN_BJF97), color="0.85",
                 label="BJF97 median $\\pm\\sigma$")
    left.axhline(bjf, color="k", lw=1)
    left.plot(n, rock, "o", ms=3, label="rock")
    med = sorted(rock)[len(rock) // 2]
    left.axhline(med, color="C0", ls="--", lw=1,
                 label=f"median rock {med:.3f} g")
    if any(abs(a - b) > 1e-12 for a, b in zip(pga, rock)):
        left.plot(n, pga, "s", ms=3, color="C3", label="with the site")
    left.set_xlabel("realisation")
    left.set_ylabel("PGA (g)")
    left.set_yscale("log")
    left.legend(fontsize=8)
    left.grid(True, alpha=0.3)
    left.set_title("PGA against BJF97")

    h, d = read(os.path.join(out, "fourier.csv"))
    f = column(h, d, "frequency")
    right.loglog(f, column(h, d, "target_rock"), "k-", lw=1,
                 label="target, rock")
    right.loglog(f, column(h, d, "mean_rock"), "C0--", lw=1,
                 label="mean of realisations, rock")
    site = column(h, d, "site_amplification")
    if any(abs(a - 1) > 1e-12 for a in site):
        right.loglog(f, column(h, d, "target"), "k-", lw=2, alpha=0.5,
                     label="target, with the site")
        right.loglog(f, column(h, d, "mean"), "C3--", lw=1,
                     label="mean, with the site")
        r2 = right.twinx()
        r2.semilogx(f, site, "C2:", lw=1)
        r2.set_ylabel("site amplification (-)", color="C2")
    right.axvspan(0.5, 10, color="0.93")
    right.set_ylim(bottom=1e-4 * max(column(h, d, "target_rock")))
    right.set_xlabel("frequency (Hz)")
    right.set_ylabel("Fourier amplitude (g s)")
    right.legend(fontsize=8, loc="lower center")
    right.grid(True, which="both", alpha=0.3)
    right.set_title("Fourier spectra (quadratic mean)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "synthetic.png"), dpi=110)


if __name__ == "__main__":
    main()
