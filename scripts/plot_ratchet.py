#!/usr/bin/python3
"""Plots of a 'ratchet-analytical' run (analytical thermal ratchet, thesis
Eqs. 5.1-5.9): sweeps.png (delta_T, delta_sigma + delta_j and delta_p per
cycle against each swept parameter), figure_5_13.png (delta_p in mm/yr
against wedge length, thesis Fig. 5-13, with the thesis's end values) and
field_cycle.png (alpha against beta from Eq. 5.9, thesis Fig. 5-11B).
Usage: plot_ratchet.py OUTPUT_DIR [QUANTITY=VALUE ...]
The values of summary.csv (figure_5_13_beta_1, figure_5_13_alpha_1, ...,
field_skin_depth, plastic_displacement) are read from OUTPUT_DIR/summary.csv
if it exists and from QUANTITY=VALUE arguments otherwise (the analysis
passes them, since the driver writes summary.csv after the run)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Thesis Fig. 5-13 (Block 1, wedge 0 and 200 mm) and Fig. 5-11B.
THESIS_FIG_5_13 = {(0.45, 8e-6): (0.181, 0.210), (0.7, 6e-6): (0.238, 0.260)}
THESIS_FIG_5_11 = [(0.45, 8e-6), (0.7, 6e-6)]

SWEEPS = [("wedge_length", "wedge length L_W (mm)", 1e3),
          ("beta", "beta (-)", 1.0),
          ("thermal_expansion", "alpha (1e-6 / K)", 1e6),
          ("temperature_amplitude", "temperature amplitude (K)", 1.0),
          ("friction_angle", "friction angle phi (deg)", 1.0),
          ("slope", "slope eta (deg)", 1.0)]


def read_table(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    header = rows[0]
    columns = {h: [float(r[i]) for r in rows[1:]] for i, h in enumerate(header)}
    return header, columns


def read_summary(path):
    with open(path) as f:
        return {r["quantity"]: r["value"] for r in csv.DictReader(f)}


def plot_sweeps(folder, summary):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for ax, (name, label, scale) in zip(axes.flat, SWEEPS):
        path = os.path.join(folder, f"sweep_{name}.csv")
        if not os.path.exists(path):
            ax.set_visible(False)
            continue
        header, c = read_table(path)
        x = [v * scale for v in c[header[0]]]
        mm = lambda key: [1e3 * v for v in c[key]]  # noqa: E731
        resist = [1e3 * (a + b) for a, b in
                  zip(c["elastic_displacement_m"], c["joint_displacement_m"])]
        ax.plot(x, mm("thermal_displacement_m"), "C1--", label="delta_T (Eq. 5.2)")
        ax.plot(x, resist, "C2:", label="delta_sigma + delta_j (5.4, 5.5)")
        ax.plot(x, mm("plastic_displacement_m"), "C0-", lw=2, label="delta_p (5.6)")
        ax.set_xlabel(label)
        ax.set_ylabel("per cycle (mm)")
        ax.grid(True, alpha=0.3)
        ax.set_ylim(bottom=0)
    axes.flat[0].legend(fontsize=8)
    fig.suptitle("ratchet-analytical: sensitivity of the permanent displacement "
                 "per cycle (other inputs at the case's values; "
                 f"case: delta_p = {1e3 * float(summary['plastic_displacement']):.4g} mm)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "sweeps.png"), dpi=110)
    plt.close(fig)


def plot_figure_5_13(folder, summary):
    header, c = read_table(os.path.join(folder, "statistics.csv"))
    x = [1e3 * v for v in c["wedge_length_m"]]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for i, colour in (("1", "C0"), ("2", "C3")):
        beta = float(summary[f"figure_5_13_beta_{i}"])
        alpha = float(summary[f"figure_5_13_alpha_{i}"])
        ax.plot(x, c[f"ratchet_rate_{i}_mm_yr"], "-", color=colour,
                label=f"rockdda, beta = {beta:g}, alpha = {alpha:g} /K")
        for (tb, ta), ends in THESIS_FIG_5_13.items():
            if abs(tb - beta) < 1e-9 and abs(ta - alpha) < 1e-15:
                ax.errorbar([0, 200], ends, yerr=[0.2 * e for e in ends],
                            fmt="s", color=colour, capsize=4, mfc="none",
                            label=f"thesis Fig. 5-13 ends (+-20 %)")
    ax.set_xlabel("wedge length L_W (mm)")
    ax.set_ylabel("permanent displacement delta_p (mm/yr)")
    ax.set_title("Thermal ratchet of Masada Block 1 (thesis Fig. 5-13)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "figure_5_13.png"), dpi=110)
    plt.close(fig)


def plot_field_cycle(folder, summary):
    header, c = read_table(os.path.join(folder, "field_cycle.csv"))
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(c["beta"], [1e6 * a for a in c["alpha_1_K"]], "C0-",
            label="Eq. 5.9")
    ax.plot([b for b, _ in THESIS_FIG_5_11], [1e6 * a for _, a in THESIS_FIG_5_11],
            "ks", mfc="none", label="thesis Fig. 5-11B")
    ax.set_xlabel("beta (-)")
    ax.set_ylabel("alpha (1e-6 / K)")
    ax.set_title(f"alpha from a field cycle (S_d = "
                 f"{float(summary['field_skin_depth']):.3g} m)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "field_cycle.png"), dpi=110)
    plt.close(fig)


def main(folder, arguments):
    path = os.path.join(folder, "summary.csv")
    summary = read_summary(path) if os.path.exists(path) else {}
    summary.update(a.split("=", 1) for a in arguments)
    plot_sweeps(folder, summary)
    plot_figure_5_13(folder, summary)
    plot_field_cycle(folder, summary)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".", sys.argv[2:])
