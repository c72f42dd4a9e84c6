#!/usr/bin/python3
"""Plot the earthquakes inside a rockdda 'ratchet' run:
OUTPUT_DIR/ratchet_earthquakes.png.

usage: plot_ratchet_earthquakes.py OUTPUT_DIR

Left: displacement of the block down the bedding plane against the year:
the thermal run alone (earthquake_yearly.csv, catalogue 0) and each
catalogue's coupled history (thermal cycles and earthquakes on one DDA
state), its events marked. Right: per catalogue, the coupled displacement
against the sum of the thermal run alone and the earthquakes alone (on the
scene without cycles, and on Block 1 alone), with the 1:1 line
(earthquake_histories.csv).
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
    yearly = table(os.path.join(out, "earthquake_yearly.csv"))
    hist = table(os.path.join(out, "earthquake_histories.csv"))
    events = table(os.path.join(out, "earthquake_events.csv"))
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))

    series = {}
    for r in yearly:
        series.setdefault(int(r["catalogue"]), []).append(
            (r["year"], 1e3 * r["displacement_m"]))
    for c, pts in sorted(series.items()):
        xs, ys = zip(*pts)
        if c == 0:
            left.plot(xs, ys, color="k", lw=2.2, label="thermal cycles alone")
        else:
            left.plot(xs, ys, lw=1, alpha=0.8,
                      label="with earthquakes" if c == 1 else None)
            colour = left.lines[-1].get_color()
            for e in events:
                if int(e["catalogue"]) == c and e["runs"] > 0:
                    year = int(e["time_yr"]) + 1
                    if year <= len(ys):
                        left.plot([year], [ys[year - 1]], "v", color=colour,
                                  ms=4 + 2 * (e["magnitude"] - 6))
    left.set_xlabel("year (one seasonal cycle a year)")
    left.set_ylabel("displacement down the bedding plane (mm)")
    left.set_title("coupled DDA histories (▼: earthquakes, size ~ Mw)")
    left.legend(loc="upper left")
    left.grid(alpha=0.3)

    xs_scene, xs_block, ys = [], [], []
    for h in hist:
        thermal = 1e3 * h["thermal_m"]
        ys.append(1e3 * h["coupled_m"])
        xs_scene.append(thermal + 1e3 * h["quakes_scene_m"])
        xs_block.append(thermal + 1e3 * h["quakes_block1_m"])
    right.plot(xs_scene, ys, "o", label="thermal + earthquakes alone (scene)")
    right.plot(xs_block, ys, "s", mfc="none",
               label="thermal + earthquakes alone (Block 1)")
    lo = min(xs_scene + xs_block + ys)
    hi = max(xs_scene + xs_block + ys)
    right.plot([lo, hi], [lo, hi], "k--", lw=1, label="1:1")
    right.set_xlabel("sum of the separate histories (mm)")
    right.set_ylabel("coupled history (mm)")
    right.set_title("combined against thermal + seismic, per catalogue")
    right.legend(loc="upper left")
    right.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "ratchet_earthquakes.png"), dpi=120)


if __name__ == "__main__":
    main()
