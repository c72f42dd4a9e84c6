#!/usr/bin/python3
"""Voussoir check of issue 16: the critical friction angle of a jointed
roof bed by bisection in DDA, against the Voussoir-beam estimate.

usage: study.py ROCKDDA [--low 5] [--high 80] [--tolerance 0.5]
                [--end-time 3] [--time-step 0.0005] [--dynamic 0.99]
                [--penalty 1e10] [--out DIR]

The bed of Hatzor & Benary (1998, Tel Beer-Sheva): span 7 m, 0.5 m thick,
vertical joints every 0.25 m (28 blocks, beam.py), between fixed
abutments, released under gravity. A run is 'collapsed' when the block
left of midspan has fallen by more than the bed thickness (0.5 m) or
still drops by more than 1 cm in the last third of the run (no
equilibrium), or the run fails; 'stable' otherwise (the bed has stopped:
its sag, in runs-*.csv, may be several cm after a slip at the abutments
that re-arches it). The bisection keeps a stable friction angle above and a collapsed one below
until they are within the tolerance (deg). Writes runs.csv (every run),
result.md (DDA against voussoir.py) into DIR (default: this folder).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import shutil
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import beam  # noqa: E402
import voussoir  # noqa: E402

THICKNESS = 0.5
MOVING = 0.01   # m: a midspan still dropping this much in the last third


def run(rockdda, folder, phi, a):
    """(classification, midspan uy (m), abutment-block uy (m), steps, cuts,
    wall time (s), diagnosis) of one DDA run at friction angle PHI."""
    name = "phi-%.4f" % phi
    scene = os.path.join(folder, name + ".dda")
    with open(scene, "w") as f:
        f.write(beam.scene(phi, spacing=a.joint_spacing))
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
    stats = os.path.join(out, "statistics.csv")
    rows = list(csv.DictReader(open(stats))) if os.path.exists(stats) else []
    if not rows:
        return ("collapsed", float("nan"), float("nan"), "", "", "", diag)
    uy, uy2 = float(rows[-1]["mp1_uy_m"]), float(rows[-1]["mp2_uy_m"])
    # The midspan's drop over the last third of the run.
    t_end = float(rows[-1]["time_s"])
    before = [r for r in rows
              if float(r["time_s"]) <= 2.0 * t_end / 3.0 + 1e-9]
    drop = float(before[-1]["mp1_uy_m"]) - uy if before else float("inf")
    if diag or uy < -THICKNESS or drop > MOVING:
        c = "collapsed"
    else:
        c = "stable"
    return (c, uy, uy2, s.get("steps", ""), s.get("time_step_cuts", ""),
            s.get("wall_time", ""), diag)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("--low", type=float, default=5.0)
    p.add_argument("--high", type=float, default=80.0)
    p.add_argument("--tolerance", type=float, default=0.5)
    p.add_argument("--end-time", type=float, default=3.0)
    p.add_argument("--time-step", type=float, default=0.0005)
    p.add_argument("--dynamic", type=float, default=0.99)
    p.add_argument("--penalty", default="1e10")
    p.add_argument("--out", default=HERE)
    p.add_argument("--joint-spacing", type=float, default=0.25)
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
        print("not stable at the upper bound %g deg: no critical angle" % hi)
        lo = hi = float("nan")
    elif trial(lo) == "stable":
        print("stable at the lower bound %g deg" % lo)
        hi = lo
    while hi - lo > a.tolerance:
        mid = 0.5 * (lo + hi)
        if trial(mid) == "stable":
            hi = mid
        else:
            lo = mid
    n_joints = int(round(7.0 / a.joint_spacing)) + 1
    v = voussoir.voussoir(7.0, THICKNESS, 2300 * 9.80665, 15.3e9,
                          joints=n_joints, joint_stiffness=float(a.penalty))
    if v is None:
        v = {"phi_req": float("nan"), "n": float("nan"),
             "f_m": float("nan"), "thrust": float("nan"),
             "deflection": float("nan")}
    tag = a.tag
    with open(os.path.join(a.out, "runs%s.csv" % tag), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["phi_deg", "result", "midspan_uy_m", "abutment_block_uy_m",
                    "steps", "cuts", "wall_time_s", "diagnosis"])
        for r in sorted(runs):
            w.writerow(r)
    with open(os.path.join(a.out, "result%s.md" % tag), "w") as f:
        f.write("Critical friction angle of the jointed bed (span 7 m, 0.5 m, "
                "joints %g m; end time %g s, dt %g s, dynamic control %g, "
                "penalty %s N/m):\n\n" % (a.joint_spacing, a.end_time, a.time_step, a.dynamic,
                                         a.penalty))
        f.write("- DDA (bisection): between %.2f deg (collapsed) "
                "and %.2f deg (stable): %.1f deg\n" % (lo, hi, 0.5 * (lo + hi)))
        f.write("- Voussoir (voussoir.py, E = 15.3 GPa, joints as springs of the "
                "penalty; nan = snap-through): %.2f deg (n = %.3f, "
                "f_m = %.3g MPa, thrust %.3g kN/m, deflection %.2g mm)\n"
                % (v["phi_req"], v["n"], v["f_m"] / 1e6, v["thrust"] / 1e3,
                   1e3 * v["deflection"]))
    table = os.path.join(a.out, "critical.csv")
    new = not os.path.exists(table)
    with open(table, "a", newline="") as f:
        w = csv.writer(f)
        if new:
            w.writerow(["case", "time_step_s", "dynamic_control", "penalty_N_m",
                        "joint_spacing_m", "end_time_s", "phi_collapsed_deg",
                        "phi_stable_deg", "phi_voussoir_deg", "runs"])
        w.writerow([tag.lstrip("-") or "default", a.time_step, a.dynamic,
                    a.penalty, a.joint_spacing, a.end_time, "%.3f" % lo,
                    "%.3f" % hi, "%.2f" % v["phi_req"], len(runs)])
    shutil.rmtree(folder, ignore_errors=True)
    print("DDA critical friction angle: %.2f-%.2f deg; Voussoir: %.2f deg"
          % (lo, hi, v["phi_req"]))


if __name__ == "__main__":
    main()
