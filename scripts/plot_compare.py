#!/usr/bin/python3
"""Plot a rockdda 'compare' run: OUTPUT_DIR/compare.png (thesis Fig. 5-19).

usage: plot_compare.py OUTPUT_DIR

Left: displacement rates of Block 1 over the window (log scale): the thermal
ratchet for each (beta, alpha) curve at the start of the window and its mean
over the window (rates.csv), the seismic rate of DDA and of the rigid block
over the catalogues (median, 16-84 %), the sum of the separate rates and the
combined history (catalogues.csv, spreads.csv). Right: cumulative
displacement against time: the thermal history alone and the combined
history (median and 16-84 % over the catalogues; histories.csv), with each
catalogue's seismic total at the end.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from rockdda_csv import table  # noqa: E402


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    out = sys.argv[1]
    rates = table(os.path.join(out, "rates.csv"))
    cats = table(os.path.join(out, "catalogues.csv"))
    hist = table(os.path.join(out, "histories.csv"))
    # spreads.csv rows: seismic, seismic_rigid, combined, sum.
    spreads = table(os.path.join(out, "spreads.csv"))
    years = hist[-1]["year"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))

    labels, values, lows, highs, colours = [], [], [], [], []
    for r in rates:
        labels.append(f"thermal\nstart\nβ={r['beta']:g}")
        values.append(r["rate_initial_mm_yr"])
        lows.append(0.)
        highs.append(0.)
        colours.append("C3")
        labels.append(f"thermal\n{years:g} yr\nβ={r['beta']:g}")
        values.append(r["rate_window_mm_yr"])
        lows.append(0.)
        highs.append(0.)
        colours.append("C1")
    for row, label, colour in ((0, "seismic\nDDA", "C0"),
                               (1, "seismic\nrigid", "C9"),
                               (3, "thermal +\nseismic", "C7"),
                               (2, "combined\nhistory", "C2")):
        med = spreads[row]["rate_median_mm_yr"]
        labels.append(label)
        values.append(med)
        lows.append(med - spreads[row]["rate_p16_mm_yr"])
        highs.append(spreads[row]["rate_p84_mm_yr"] - med)
        colours.append(colour)
    x = range(len(values))
    left.bar(x, values, color=colours, yerr=[lows, highs], capsize=3)
    left.set_yscale("log")
    left.set_xticks(list(x))
    left.set_xticklabels(labels, fontsize=7)
    left.set_ylabel("displacement rate (mm/yr)")
    left.set_title(f"Block 1 over {years:g} yr, {len(cats)} catalogues "
                   "(medians, 16-84 %)", fontsize=9)
    left.grid(True, axis="y", alpha=0.3)

    t = [h["year"] for h in hist]
    right.plot(t, [1e3 * h["thermal_m"] for h in hist], "C1",
               label="thermal alone (β curve 1)")
    right.plot(t, [1e3 * h["combined_median_m"] for h in hist], "C2",
               label="combined, median")
    right.fill_between(t, [1e3 * h["combined_p16_m"] for h in hist],
                       [1e3 * h["combined_p84_m"] for h in hist],
                       color="C2", alpha=0.25, label="combined, 16-84 %")
    right.plot([years] * len(cats), [1e3 * c["seismic_m"] for c in cats],
               "C0.", label="seismic alone, each catalogue")
    right.set_xlabel("years")
    right.set_ylabel("cumulative displacement (mm)")
    right.legend(fontsize=8, loc="upper left")
    right.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "compare.png"), dpi=110)


if __name__ == "__main__":
    main()
