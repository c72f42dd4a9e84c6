#!/usr/bin/env python3
"""The thesis's shaking-table wedge (Sec. 4.6-4.7.2, Fig. 4-6) in 3D DDA
against the analytical rigid wedge: for each seismic mode, contact penalty
and time step, run parameter-files/dda3d-shaking-table.prm with them
replaced and compare the wedge's displacement history (relative to the
ground in the displacement mode) with parameter-files/
sliding3d-shaking-table.prm (dt = 1e-4 s).

usage: shaking_table.py ROCKDDA BLOCKS [--modes loading,displacement]
       [--penalty 1e10,2e10,...] [--dt 0.005,...] [--end 22.4 (s; the record is 2.4 s shorter:
       the filter's padding)]
       [--contact-damping 0,1,...] [--step-damping 0,1,...]
       [--strain-damping 0,1e-4,...] [--stiff-velocity false,true]
       [--shared-strength false,true] [--shear-ratio 0.4,0.04,...]
       [--shear-penalty 0,4e9,... (N/m; 0: the ratio x the penalty)]
       [--out shaking_table.csv] [--histories DIR]

Columns: mode, dt_s, penalty_N_per_m, status (ok, or the run's failure),
final slide (m, along the line of intersection), error_final (|u - u_a|
at the end / |u_a| at the end), error_history (max over t of |u - u_a| /
|u_a| at the end), onset_s (first time the slide exceeds 1e-4 m; the
analytical onset in the row 'analytical'; the input acceleration at the
onset against the yield acceleration is checked by the unit test), wall_s, steps, cuts. --histories keeps each run's statistics.csv as
DIR/MODE-DT-PENALTY[-cdZETA][-sbBETA][-sdETA][-sv].csv; contact_damping,
contact_step_damping, strain_damping_s, stiff_velocity (key "Stiff mode
velocity"), shared_strength (key "Face group shared strength", history
names -ss), shear_ratio (key "Shear penalty ratio", history names -srX),
shear_penalty_N_per_m (key "Shear penalty", history names -ksX). Every
one of these keys is written into the run's parameter file, so the
defaults here (false, false, 0.4, 0: Shi's velocity, each contact its own
strength, the shear penalty 0.4 x the normal one) override the documented
setting of the template (stiff-mode velocity, shared strength, 4e9 N/m):
pass --stiff-velocity true --shared-strength true --shear-penalty 4e9 for
it.
"""
import argparse
import csv
import itertools
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PRM = os.path.join(HERE, "..", "..", "parameter-files")
sys.path.insert(0, os.path.join(HERE, "..", "dda3d"))
from fig4_2_error import summary  # noqa: E402

# Keys of the DDA 3d section that the template leaves at their defaults.
OPTIONAL = ("Contact damping ratio", "Contact step damping", "Strain damping",
            "Stiff mode velocity", "Face group shared strength",
            "Shear penalty ratio", "Shear penalty")
ONSET = 1e-4  # m: 1e3 x the elastic slip of the contact springs at 1e10 N/m


def table(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return [dict(zip(rows[0], map(float, r))) for r in rows[1:]]


def run(rockdda, template, replace, work, name, blocks=None):
    text = open(template).read()
    for key, value in replace.items():
        # A list gives the values of the key's occurrences in order.
        values = iter(value if isinstance(value, list) else [value])
        text, n = re.subn(rf"(set {re.escape(key)}\s*=).*",
                          lambda m: f"{m.group(1)} {next(values)}", text)
        if n == 0 and key in OPTIONAL:  # a key at its default: add it
            text, n = re.subn(r"(\n(\s*)set Contact penalty\s*=.*)",
                              rf"\g<1>\n\g<2>set {key} = {value}", text)
        assert n == (len(value) if isinstance(value, list) else 1), key
    text = re.sub(r"set Output directory\s*=.*",
                  f"set Output directory = {name}", text)
    if blocks:
        text = text.replace("dda3d-shaking-table.blocks",
                            os.path.abspath(blocks))
        text = re.sub(r"set Output interval(\s*)=.*",
                      r"set Output interval\1= 0", text)
    prm = os.path.join(work, name + ".prm")
    open(prm, "w").write(text)
    start = time.perf_counter()
    p = subprocess.run([rockdda, "--quiet", prm], cwd=work,
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                       text=True)
    wall = time.perf_counter() - start
    status = "ok" if p.returncode == 0 else \
        (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
    return os.path.join(work, name), status, wall


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("blocks")
    p.add_argument("--modes", default="loading,displacement")
    p.add_argument("--penalty", default="1e10,2e10,4e10")
    p.add_argument("--dt", default="0.005")
    p.add_argument("--end", default="22.4")
    p.add_argument("--contact-damping", default="0",
                   help="Contact damping ratios (-), comma-separated")
    p.add_argument("--step-damping", default="0",
                   help="Contact step damping values (-), comma-separated")
    p.add_argument("--strain-damping", default="0",
                   help="Strain damping values (s), comma-separated")
    p.add_argument("--stiff-velocity", default="false",
                   help="Stiff mode velocity values (false, true), "
                   "comma-separated")
    p.add_argument("--shared-strength", default="false",
                   help="Face group shared strength values (false, true), "
                   "comma-separated")
    p.add_argument("--shear-ratio", default="0.4",
                   help="Shear penalty ratio values (-), comma-separated")
    p.add_argument("--shear-penalty", default="0",
                   help="Shear penalty values (N/m; 0: the ratio x the "
                   "normal penalty), comma-separated")
    p.add_argument("--out", default="shaking_table.csv")
    p.add_argument("--histories")
    a = p.parse_args()
    a.rockdda = os.path.abspath(a.rockdda)
    work = tempfile.mkdtemp(prefix="dda3d-shaking-table-")
    # The record: End time less the filter's two pads (0.75 x 4 / 2.5 s).
    record = f"{float(a.end) - 2.4:g}"
    ref, status, _ = run(a.rockdda,
                         os.path.join(PRM, "sliding3d-shaking-table.prm"),
                         {"Duration": [record, a.end]}, work, "analytical")
    assert status == "ok", status
    an = table(os.path.join(ref, "statistics.csv"))
    t_a = [r["time_s"] for r in an]
    u_a = [tuple(r[f"displacement_{c}_m"] for c in "xyz") for r in an]
    end = u_a[-1]
    scale = math.hypot(*end)
    # The sliding direction (the line of intersection, down).
    line = tuple(x / scale for x in end)

    def at(t):
        k = min(range(len(t_a)), key=lambda i: abs(t_a[i] - t))
        return u_a[k]

    onset_a = next((t for t, u in zip(t_a, u_a) if math.hypot(*u) > ONSET),
                   float("nan"))
    rows = [["analytical", "1e-4", "-", "ok",
             f"{sum(e * l for e, l in zip(end, line)):.6f}", "0", "0",
             f"{onset_a:.3f}", "", "", "", "", "", "", "", "", "", ""]]
    print(*rows[-1], flush=True)
    if a.histories:
        os.makedirs(a.histories, exist_ok=True)
        shutil.copy(os.path.join(ref, "statistics.csv"),
                    os.path.join(a.histories, "analytical.csv"))
    for mode, zeta, beta, eta, sv, ss, sr, ks, dt, pen in itertools.product(
            a.modes.split(","), a.contact_damping.split(","),
            a.step_damping.split(","), a.strain_damping.split(","),
            a.stiff_velocity.split(","), a.shared_strength.split(","),
            a.shear_ratio.split(","), a.shear_penalty.split(","),
            a.dt.split(","),
            a.penalty.split(",")):
        name = f"{mode}-{dt}-{pen}"
        replace = {"Time step": ["0.005", dt], "Contact penalty": pen,
                   "Seismic input": mode, "End time": a.end,
                   "Duration": record, "Stiff mode velocity": sv,
                   "Face group shared strength": ss,
                   "Shear penalty ratio": sr, "Shear penalty": ks}
        # (Keys at their defaults are left out: the history names
        # and an older driver stay as they were.)
        if zeta != "0":
            replace["Contact damping ratio"] = zeta
            name += f"-cd{zeta}"
        if beta != "0":
            replace["Contact step damping"] = beta
            name += f"-sb{beta}"
        if eta != "0":
            replace["Strain damping"] = eta
            name += f"-sd{eta}"
        if sv != "false":
            name += "-sv"
        if ss != "false":
            name += "-ss"
        if sr != "0.4":
            name += f"-sr{sr}"
        if ks != "0":
            name += f"-ks{ks}"
        out, status, wall = run(
            a.rockdda, os.path.join(PRM, "dda3d-shaking-table.prm"),
            replace, work, name, a.blocks)
        stats = os.path.join(out, "statistics.csv")
        if not os.path.exists(stats):
            rows.append([mode, dt, pen, status] + [""] * 7
                        + [zeta, beta, eta, sv, ss, sr, ks])
            print(*rows[-1], flush=True)
            continue
        hist = table(stats)
        err_h, onset, u = 0., float("nan"), (0., 0., 0.)
        for r in hist:
            u = tuple(r[f"mp1_u{c}_m"] - r.get(f"ground_u{c}_m", 0.)
                      for c in "xyz")
            if math.isnan(onset) and math.hypot(*u) > ONSET:
                onset = r["time_s"]
            err_h = max(err_h, math.dist(u, at(r["time_s"])) / scale)
        s = summary(out) if status == "ok" else {}
        err_f = math.dist(u, end) / scale
        rows.append([mode, dt, pen, status,
                     f"{sum(e * l for e, l in zip(u, line)):.6f}",
                     f"{err_f:.3e}", f"{err_h:.3e}", f"{onset:.3f}",
                     f"{wall:.2f}",
                     int(s.get("steps", 0)),
                     int(s.get("time_step_cuts", 0)), zeta, beta, eta, sv,
                     ss, sr, ks])
        print(*rows[-1], flush=True)
        if a.histories:
            shutil.copy(stats, os.path.join(a.histories,
                                            name + ".csv"))
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["mode", "dt_s", "penalty_N_per_m", "status", "slide_m",
                    "error_final", "error_history", "onset_s", "wall_s", "steps", "cuts",
                    "contact_damping", "contact_step_damping",
                    "strain_damping_s", "stiff_velocity", "shared_strength",
                    "shear_ratio", "shear_penalty_N_per_m"])
        w.writerows(rows)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
