#!/usr/bin/python3
"""Voussoir check of issue 16: the critical friction angle of a jointed
roof bed by bisection in DDA, against the Voussoir-beam estimate.

usage: study.py ROCKDDA [--low 5] [--high 80] [--tolerance 0.5]
                [--end-time 3] [--time-step 0.001] [--dynamic 0.99]
                [--penalty 1e10] [--out DIR]

The bed of Hatzor & Benary (1998, Tel Beer-Sheva): span 7 m, 0.5 m thick,
vertical joints every 0.25 m (28 blocks, beam.py), between fixed
abutments, released under gravity. A run is 'collapsed' when the block
left of midspan has moved down by more than half the bed thickness
(0.25 m) at the end time, 'stable' when by less than 0.05 m, else
'undecided' (reported; the bisection then treats it as collapsed). The
bisection keeps a stable friction angle above and a collapsed one below
until they are within the tolerance (deg). Writes runs.csv (every run),
result.md (DDA against voussoir.py) into DIR (default: this folder).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import beam  # noqa: E402
import voussoir  # noqa: E402

THICKNESS = 0.5


def run(rockdda, folder, phi, a):
    """(classification, midspan uy (m), abutment-block uy (m), steps, cuts,
    wall time (s), diagnosis) of one DDA run at friction angle PHI."""
    name = "phi-%.4f" % phi
    scene = os.path.join(folder, name + ".dda")
    with open(scene, "w") as f:
        f.write(beam.scene(phi))
    out = os.path.join(folder, name)
    text = open(os.path.join(HERE, "beam.prm.in")).read()
    for k, v in (("@OUT@", out), ("@SCENE@", scene),
                 ("@END@", repr(a.end_time)), ("@DT@", repr(a.time_step)),
                 ("@DYNAMIC@", repr(a.dynamic)), ("@PENALTY@", a.penalty)):
        text = text.replace(k, v)
    prm = os.path.join(folder, name + ".prm")
    with open(prm, "w") as f:
        f.write(text)
    p = subprocess.run([rockdda, "--quiet", prm], capture_output=True,
                       text=True)
    s = {}
    path = os.path.join(out, "summary.csv")
    if os.path.exists(path):
        for row in csv.reader(open(path)):
            if len(row) >= 2:
                s[row[0]] = row[1]
    diag = ""
    if p.returncode != 0 or s.get("completed") != "1":
        for line in open(os.path.join(out, "log.txt"), errors="replace") \
                if os.path.exists(os.path.join(out, "log.txt")) else []:
            if "DDA stopped: " in line:
                diag = line.split("DDA stopped: ", 1)[1].strip()
        diag = diag or (p.stderr.strip().splitlines() or ["failed"])[-1]
        # A failed run: take the last row of statistics.csv.
        stats = os.path.join(out, "statistics.csv")
        rows = list(csv.DictReader(open(stats))) if os.path.exists(stats) \
            else []
        uy = float(rows[-1]["mp1_uy"]) if rows else float("nan")
        uy2 = float(rows[-1]["mp2_uy"]) if rows else float("nan")
    else:
        uy, uy2 = float(s["mp1_uy"]), float(s["mp2_uy"])
    if uy < -0.5 * THICKNESS:
        c = "collapsed"
    elif uy > -0.1 * THICKNESS and not diag:
        c = "stable"
    else:
        c = "undecided"
    return (c, uy, uy2, s.get("steps", ""), s.get("time_step_cuts", ""),
            s.get("wall_time", ""), diag)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("--low", type=float, default=5.0)
    p.add_argument("--high", type=float, default=80.0)
    p.add_argument("--tolerance", type=float, default=0.5)
    p.add_argument("--end-time", type=float, default=3.0)
    p.add_argument("--time-step", type=float, default=0.001)
    p.add_argument("--dynamic", type=float, default=0.99)
    p.add_argument("--penalty", default="1e10")
    p.add_argument("--out", default=HERE)
    p.add_argument("--tag", default="")
    a = p.parse_args()
    folder = tempfile.mkdtemp(prefix="voussoir-")
    runs = []

    def trial(phi):
        r = run(a.rockdda, folder, phi, a)
        runs.append((phi,) + r)
        print("phi %.3f deg: %s, midspan uy %.4g m, abutment block uy %.4g m,"
              " %s steps, %s cuts, %s s %s" % ((phi,) + r), flush=True)
        return r[0]

    lo, hi = a.low, a.high
    if trial(hi) != "stable":
        raise SystemExit("not stable at the upper bound %g deg" % hi)
    if trial(lo) == "stable":
        raise SystemExit("stable at the lower bound %g deg" % lo)
    while hi - lo > a.tolerance:
        mid = 0.5 * (lo + hi)
        if trial(mid) == "stable":
            hi = mid
        else:
            lo = mid
    v = voussoir.voussoir(7.0, THICKNESS, 2300 * 9.80665, 15.3e9)
    tag = a.tag
    with open(os.path.join(a.out, "runs%s.csv" % tag), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["phi_deg", "result", "midspan_uy_m", "abutment_block_uy_m",
                    "steps", "cuts", "wall_time_s", "diagnosis"])
        for r in sorted(runs):
            w.writerow(r)
    with open(os.path.join(a.out, "result%s.md" % tag), "w") as f:
        f.write("Critical friction angle of the jointed bed (span 7 m, 0.5 m, "
                "joints 0.25 m; end time %g s, dt %g s, dynamic control %g, "
                "penalty %s N/m):\n\n" % (a.end_time, a.time_step, a.dynamic,
                                         a.penalty))
        f.write("- DDA (bisection): between %.2f deg (collapsed or undecided) "
                "and %.2f deg (stable): %.1f deg\n" % (lo, hi, 0.5 * (lo + hi)))
        f.write("- Voussoir (voussoir.py, E = 15.3 GPa): %.2f deg (n = %.3f, "
                "f_m = %.3g MPa, thrust %.3g kN/m, deflection %.2g mm)\n"
                % (v["phi_req"], v["n"], v["f_m"] / 1e6, v["thrust"] / 1e3,
                   1e3 * v["deflection"]))
    print("DDA critical friction angle: %.2f-%.2f deg; Voussoir: %.2f deg"
          % (lo, hi, v["phi_req"]))


if __name__ == "__main__":
    main()
