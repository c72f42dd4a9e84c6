#!/usr/bin/python3
"""Time to solution of the two brick walls released from rest
(../shared/data/dda-scenes: wall-25x40, 1,013 blocks, 0.3 s; wall-50x80,
4,026 blocks, 0.1 s), run through the rockdda driver with the scenes' own
parameter files.

For each binary, scene and thread count it runs REPEAT times (binaries
alternating, so that a baseline and the current build see the same machine
state) and writes one CSV row of medians: steps, cuts, open-close
iterations per accepted step, linear solves, ms per step, wall time to the
end (the driver's own timer), peak resident memory, and the mean settlement
of the top row of bricks at the end (settlement.py).

  from_rest.py [--repeat N] [--threads 1,2] [--scenes wall-25x40,wall-50x80]
               [--scene-dir DIR] NAME=BINARY[:OPTION=VALUE...] [...] > from-rest.csv

--scene-dir reads the scenes (SCENE.prm and its block file) from DIR
instead, e.g. the larger walls of make_wall.py.

OPTIONs of a configuration (issue 16, distributed DDA): np=N runs it with
'mpirun -np N' (ranks, column 'ranks'); threads=T fixes its threads
(otherwise each of --threads); solver=S and pc=P set 'Linear solver' and
'Distributed preconditioner'; tol=F sets 'Contact force tolerance' (issue
12's accuracy knob) and dt=H the 'Time step' (s). The column 'time_ratio' is the median over
the rounds of the time to the end divided by that of the first
configuration on the same scene in the same round (binaries alternate
within a round).
"""
import argparse
import csv
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data",
                                     "dda-scenes"))


def summary(path):
    out = {}
    with open(path) as f:
        for row in csv.reader(f):
            if len(row) == 3:
                out[row[0]] = row[1]
    return out


def parse_spec(text):
    """NAME=BINARY[:OPTION=VALUE...] -> (name, binary, options)."""
    name, rest = text.split("=", 1)
    parts = rest.split(":")
    options = dict(o.split("=", 1) for o in parts[1:])
    return name, parts[0], options


def run(binary, scene, threads, work, options=None, data=DATA):
    options = options or {}
    prm = open(os.path.join(data, scene + ".prm")).read()
    end = float(re.search(r"set End time\s*=\s*(\S+)", prm).group(1))
    out = os.path.join(work, "out")
    prm = re.sub(r"set Output directory\s*=.*", "set Output directory = " + out,
                 prm)
    prm = re.sub(r"set Block file\s*=\s*(\S+)",
                 lambda m: "set Block file = "
                 + os.path.join(data, m.group(1)), prm)
    prm = re.sub(r"set Threads\s*=.*", "set Threads = %d" % threads, prm)
    extra = ""
    if "solver" in options:
        extra += "  set Linear solver = %s\n" % options["solver"]
    if "pc" in options:
        extra += "  set Distributed preconditioner = %s\n" % options["pc"]
    if "tol" in options:
        extra += "  set Contact force tolerance = %s\n" % options["tol"]
    if "dt" in options:
        prm = re.sub(r"set Time step\s*=.*", "set Time step = " + options["dt"],
                     prm)
    prm = prm.replace("subsection DDA\n", "subsection DDA\n" + extra, 1)
    # One output at the start and one at the end, for the settlement.
    prm = re.sub(r"set Output interval\s*=.*", "set Output interval = %g" % end,
                 prm)
    path = os.path.join(work, scene + ".prm")
    open(path, "w").write(prm)
    command = [binary, path]
    if int(options.get("np", 0)) > 0:
        # Plain copies between ranks (containers often forbid the
        # cross-memory attach of the shared-memory transport).
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe",
                   "--bind-to", "none", "--mca",
                   "btl_vader_single_copy_mechanism", "none",
                   "-np", options["np"]] + command
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        sys.exit("from_rest.py: %s %s failed (%d)" % (binary, path,
                                                     child.returncode))
    s = summary(os.path.join(out, "summary.csv"))
    settle = subprocess.run([sys.executable, os.path.join(HERE,
                                                          "settlement.py"),
                             out], check=True, capture_output=True,
                            text=True).stdout
    steps = float(s["steps"])
    wall = float(s["wall_time"])
    return {
        "steps": steps,
        "cuts": float(s["time_step_cuts"]),
        "iterations_per_step": float(
            s.get("open_close_iterations_per_step", "nan")),
        "linear_solves": float(s.get("linear_solves", "nan")),
        "ms_per_step": 1e3 * wall / steps,
        "time_to_end_s": wall,
        "peak_memory_MiB": usage.ru_maxrss / 1024.,
        "top_settlement_m": float(settle),
    }


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--threads", default="2")
    p.add_argument("--scenes", default="wall-25x40,wall-50x80")
    p.add_argument("--scene-dir", default=DATA)
    p.add_argument("binaries", nargs="+")
    a = p.parse_args()
    specs = [parse_spec(b) for b in a.binaries]
    w = csv.writer(sys.stdout)
    keys = ["steps", "cuts", "iterations_per_step", "linear_solves",
            "ms_per_step", "time_to_end_s", "peak_memory_MiB",
            "top_settlement_m"]
    w.writerow(["scene", "code", "ranks", "threads", "runs"] + keys
               + ["time_ratio"])
    for scene in a.scenes.split(","):
        # The (configuration, threads) pairs of this scene, in order.
        runs = []
        for threads in [int(t) for t in a.threads.split(",")]:
            for name, binary, options in specs:
                t = int(options.get("threads", threads))
                if (name, t) not in [(r[0], r[3]) for r in runs]:
                    runs.append((name, binary, options, t))
        results = {(r[0], r[3]): [] for r in runs}
        for _ in range(a.repeat):
            for name, binary, options, t in runs:
                with tempfile.TemporaryDirectory() as work:
                    results[(name, t)].append(run(binary, scene, t, work,
                                                  options, a.scene_dir))
        first = results[(runs[0][0], runs[0][3])]
        for name, _, options, t in runs:
            rows = results[(name, t)]
            ratio = statistics.median(
                r["time_to_end_s"] / f["time_to_end_s"]
                for r, f in zip(rows, first))
            w.writerow([scene, name, int(options.get("np", 1)), t, len(rows)]
                       + ["%.6g" % statistics.median(r[k] for r in rows)
                          for k in keys] + ["%.3f" % ratio])
            sys.stdout.flush()


main()
