"""Thesis Fig. 5-13 reproduced with 'rockdda ratchet-analytical'.

usage: reproduce.py ROCKDDA BLOCK1.prm OUTPUT_FOLDER

1. Runs BLOCK1.prm as it stands (the Fig. 5-9 cross-section taken as the
   L_B x H = 7 x 15 m block of Eq. 5.3) and compares delta_p at wedge lengths
   0 and 200 mm with the thesis's 0.181-0.210 mm/yr (beta 0.45, alpha 8e-6)
   and 0.238-0.260 mm/yr (beta 0.7, alpha 6e-6).
2. From that run, the factor s on F_max that makes each thesis value exact,
   s = (delta_T - delta_p,thesis) / (delta_sigma + delta_j), and their mean;
   delta_sigma + delta_j = delta_T - delta_p with delta_T of Eq. 5.2.
3. Runs the same file with the density scaled by the mean s (F_max is
   proportional to the unit weight; nothing else depends on it except the
   skin depth, which is held by scaling c_p by 1/s) to show that one
   smaller force explains the whole offset.
Writes reproduction.csv, reproduction.md and figure_5_13.png.
"""
import csv
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

THESIS = {1: (0.45, 8e-6, 0.181, 0.210), 2: (0.7, 6e-6, 0.238, 0.260)}


def run(rockdda, prm_text, folder, name):
    prm = os.path.join(folder, name + ".prm")
    with open(prm, "w") as f:
        f.write(prm_text)
    out = os.path.join(folder, "output-" + name)
    subprocess.run([rockdda, "--quiet", prm], cwd=folder, check=True)
    summary = {r["quantity"]: r["value"]
               for r in csv.DictReader(open(os.path.join(out, "summary.csv")))}
    rows = list(csv.DictReader(open(os.path.join(out, "statistics.csv"))))
    return summary, rows


def with_setting(text, key, value):
    """Replace the first 'set KEY = ...' line of the Ratchet section."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.strip().startswith("set " + key + " ") or \
                line.strip().startswith("set " + key + "="):
            indent = line[:len(line) - len(line.lstrip())]
            lines[i] = f"{indent}set {key} = {value!r}"
            return "\n".join(lines) + "\n"
    raise KeyError(key)


def main(rockdda, prm_file, here):
    text = open(prm_file).read()
    text = text.replace("set Output directory = output-ratchet-analytical",
                        "set Output directory =")
    text = text.replace("subsection Ratchet analytical",
                        "subsection Ratchet analytical\n  set Plots = false", 1)
    with tempfile.TemporaryDirectory() as tmp:
        base, rows = run(rockdda, text, tmp, "block1")
        dTp = float(base["temperature_change"])
        Sd = float(base["skin_depth"])
        wall = float(base["wall_time"])
        table, scales = [], []
        for c, (beta, alpha, th0, th200) in THESIS.items():
            for row, thesis in ((rows[0], th0), (rows[-1], th200)):
                LW = float(row["wedge_length_m"])
                dp = float(row[f"plastic_displacement_{c}_m"])
                dT = alpha * dTp * (LW + 2 * beta * Sd)
                resist = dT - dp
                s = (dT - 1e-3 * thesis) / resist
                scales.append(s)
                table.append(dict(curve=c, beta=beta, alpha=alpha,
                                  wedge_mm=1e3 * LW, thesis=thesis,
                                  rockdda=1e3 * dp, fmax_scale_fit=s))
        s = sum(scales) / len(scales)
        for line in text.splitlines():
            if line.strip().startswith("set Density"):
                rho = float(line.split("=")[1])
            if line.strip().startswith("set Specific heat capacity"):
                cp = float(line.split("=")[1])
        scaled_text = with_setting(with_setting(text, "Density", rho * s),
                                   "Specific heat capacity", cp / s)
        scaled, scaled_rows = run(rockdda, scaled_text, tmp, "block1-scaled")
        assert abs(float(scaled["skin_depth"]) - Sd) < 1e-9 * Sd
        k = 0
        for c in THESIS:
            for row in (scaled_rows[0], scaled_rows[-1]):
                table[k]["rockdda_scaled"] = 1e3 * float(
                    row[f"plastic_displacement_{c}_m"])
                k += 1
        curves = {
            "wedge_mm": [1e3 * float(r["wedge_length_m"]) for r in rows],
            1: [float(r["ratchet_rate_1_mm_yr"]) for r in rows],
            2: [float(r["ratchet_rate_2_mm_yr"]) for r in rows],
            "s1": [float(r["ratchet_rate_1_mm_yr"]) for r in scaled_rows],
            "s2": [float(r["ratchet_rate_2_mm_yr"]) for r in scaled_rows]}

    with open(os.path.join(here, "reproduction.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["curve", "beta", "alpha_1/K", "wedge_length_mm",
                    "thesis_mm/yr", "rockdda_mm/yr", "relative_difference",
                    "fmax_scale_fit", f"rockdda_fmax_x{s:.3f}_mm/yr",
                    "relative_difference_scaled"])
        for r in table:
            w.writerow([r["curve"], r["beta"], r["alpha"], f"{r['wedge_mm']:g}",
                        r["thesis"], f"{r['rockdda']:.4f}",
                        f"{r['rockdda'] / r['thesis'] - 1:+.3f}",
                        f"{r['fmax_scale_fit']:.4f}",
                        f"{r['rockdda_scaled']:.4f}",
                        f"{r['rockdda_scaled'] / r['thesis'] - 1:+.3f}"])
    with open(os.path.join(here, "reproduction.md"), "w") as f:
        f.write("| beta | alpha (1/K) | L_W (mm) | thesis (mm/yr) | rockdda "
                "(mm/yr) | difference | F_max factor fitting the thesis | "
                f"rockdda, F_max x {s:.3f} (mm/yr) | difference |\n")
        f.write("|---|---|---|---|---|---|---|---|---|\n")
        for r in table:
            f.write(f"| {r['beta']} | {r['alpha']:g} | {r['wedge_mm']:g} | "
                    f"{r['thesis']:.3f} | {r['rockdda']:.4f} | "
                    f"{100 * (r['rockdda'] / r['thesis'] - 1):+.1f} % | "
                    f"{r['fmax_scale_fit']:.3f} | {r['rockdda_scaled']:.4f} | "
                    f"{100 * (r['rockdda_scaled'] / r['thesis'] - 1):+.1f} % |\n")
        f.write(f"\nInputs: {os.path.relpath(prm_file, here)} "
                f"(Delta T_p = {dTp:g} K, S_d = {Sd:.4f} m, F_max = "
                f"{float(base['max_force']):.6g} N/m). Wall time of one run "
                f"({len(rows)} wedge lengths x 2 curves and 6 sweeps, no "
                f"plots): {1e3 * wall:.0f} ms (summary.csv wall_time).\n")

    fig, ax = plt.subplots(figsize=(7, 4.6))
    for c, colour in ((1, "C0"), (2, "C3")):
        beta, alpha, th0, th200 = THESIS[c]
        ax.plot(curves["wedge_mm"], curves[c], "-", color=colour,
                label=f"rockdda, beta {beta}, alpha {alpha:g} /K")
        ax.plot(curves["wedge_mm"], curves[f"s{c}"], ":", color=colour,
                label=f"rockdda, F_max x {s:.3f}")
        ax.errorbar([0, 200], [th0, th200], yerr=[0.2 * th0, 0.2 * th200],
                    fmt="s", mfc="none", color=colour, capsize=4,
                    label="thesis Fig. 5-13 (+-20 %)")
    ax.set_xlabel("wedge length L_W (mm)")
    ax.set_ylabel("permanent displacement delta_p (mm/yr)")
    ax.set_title("Masada Block 1: analytical thermal ratchet (thesis Fig. 5-13)",
                 fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(here, "figure_5_13.png"), dpi=110)
    print(open(os.path.join(here, "reproduction.md")).read())


if __name__ == "__main__":
    main(os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]),
         os.path.abspath(sys.argv[3]))
