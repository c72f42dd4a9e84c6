#!/usr/bin/env python3
"""Error against cost of 3D DDA on the thesis's Fig. 4-2A and 4-2B (block on
a plane 20/090, phi = 30 deg, Table 4-1's block, 2 pi s of loading-mode
input): for each time step and contact penalty, the relative error of the
final displacement vector against the analytical solution (analysis type
sliding3d at dt = 1e-5 s, converged to ~1e-5), and the wall time.

usage: fig4_2_error.py ROCKDDA [--dt 0.01,0.005,...] [--penalty 1e7,...]
       [--strain-damping 0,1e-3,...] [--contact-damping 0,0.5,...]
       [--step-damping 0,1,...]
       [--repeat 3] [--cases a,b] [--out fig4_2_error.csv]

Runs parameter-files/dda3d-fig4-2{a,b}.prm and sliding3d-fig4-2{a,b}.prm
with the time step, penalty, strain damping (Kelvin-Voigt viscous time
eta, s), contact damping ratio and contact step damping (-) replaced, in a scratch folder; writes
one CSV row per run: case, dt_s, penalty_N_per_m, strain_damping_s,
contact_damping, contact_step_damping, ux, uy, uz, error, wall_s (the median of
--repeat runs: the machine is shared), steps, cuts.
"""
import argparse
import csv
import itertools
import math
import os
import re
import statistics
import subprocess
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PRM = os.path.join(HERE, "..", "..", "parameter-files")


def summary(folder):
    out = {}
    with open(os.path.join(folder, "summary.csv")) as f:
        for row in csv.DictReader(f):
            try:
                out[row["quantity"]] = float(row["value"])
            except ValueError:
                pass
    return out


BLOCKS = os.path.join(PRM, "dda3d-fig4-2.blocks")
REPEAT = 1


def run(rockdda, template, replace, work, name):
    text = open(template).read()
    for key, value in replace.items():
        text, n = re.subn(rf"(set {re.escape(key)}\s*=).*", rf"\g<1> {value}",
                          text)
        if n == 0 and key in ("Strain damping", "Contact damping ratio",
                              "Contact step damping"):
            text, n = re.subn(r"(\n(\s*)set Time step\s*=.*)",
                              rf"\g<1>\n\g<2>set {key} = {value}", text)
        assert n == 1, key
    text = re.sub(r"set Output directory\s*=.*",
                  f"set Output directory = {name}", text)
    text = text.replace("dda3d-fig4-2.blocks",
                        os.path.abspath(BLOCKS))
    text = re.sub(r"set Output interval(\s*)=.*", r"set Output interval\1= 0",
                  text) if "DDA 3d" in text else text
    prm = os.path.join(work, name + ".prm")
    open(prm, "w").write(text)
    walls = []
    for _ in range(REPEAT):
        start = time.perf_counter()
        subprocess.run([rockdda, "--quiet", prm], cwd=work, check=True,
                       stdout=subprocess.DEVNULL)
        walls.append(time.perf_counter() - start)
    return summary(os.path.join(work, name)), statistics.median(walls)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("--dt", default="0.01,0.005,0.002,0.001")
    p.add_argument("--penalty", default="1e7,1e8,1e9")
    p.add_argument("--strain-damping", default="0",
                   help="Strain damping values (s), comma-separated")
    p.add_argument("--contact-damping", default="0",
                   help="Contact damping ratios (-), comma-separated")
    p.add_argument("--step-damping", default="0",
                   help="Contact step damping values (-), comma-separated")
    p.add_argument("--repeat", type=int, default=1,
                   help="runs per setting; the wall time is their median")
    p.add_argument("--cases", default="a,b")
    p.add_argument("--out", default="fig4_2_error.csv")
    p.add_argument("--blocks", default=os.path.join(PRM, "dda3d-fig4-2.blocks"),
                   help="block file (default: Table 4-1's block)")
    p.add_argument("--settling", default="20", help="Settling steps")
    a = p.parse_args()
    global BLOCKS, REPEAT
    BLOCKS = a.blocks
    REPEAT = a.repeat
    work = tempfile.mkdtemp(prefix="dda3d-fig4-2-")
    rows = []
    for case in a.cases.split(","):
        ref, _ = run(a.rockdda, os.path.join(PRM, f"sliding3d-fig4-2{case}.prm"),
                     {"Time step": "1e-5"}, work, f"ref-{case}")
        r = [ref["final_displacement_" + c] for c in "xyz"]
        for eta, zeta, beta, dt, pen in itertools.product(
                a.strain_damping.split(","), a.contact_damping.split(","),
                a.step_damping.split(","), a.dt.split(","),
                a.penalty.split(",")):
            name = f"dda3d-{case}-{dt}-{pen}-{eta}-{zeta}-{beta}"
            replace = {"Time step": dt, "Contact penalty": pen,
                       "Settling steps": a.settling, "Strain damping": eta}
            if zeta != "0":  # (a driver without the key runs the rest)
                replace["Contact damping ratio"] = zeta
            if beta != "0":
                replace["Contact step damping"] = beta
            s, wall = run(a.rockdda,
                          os.path.join(PRM, f"dda3d-fig4-2{case}.prm"),
                          replace, work, name)
            u = [s["mp1_u" + c] for c in "xyz"]
            err = math.dist(u, r) / math.hypot(*r)
            rows.append([case, dt, pen, eta, zeta, beta]
                        + [f"{x:.6f}" for x in u]
                        + [f"{err:.3e}", f"{wall:.2f}",
                           int(s["steps"]), int(s["time_step_cuts"])])
            print(*rows[-1], flush=True)
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "dt_s", "penalty_N_per_m", "strain_damping_s",
                    "contact_damping", "contact_step_damping",
                    "ux_m", "uy_m", "uz_m",
                    "error", "wall_s", "steps", "cuts"])
        w.writerows(rows)
    print("reference (sliding3d, dt = 1e-5 s) in", work)


if __name__ == "__main__":
    main()
