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
               NAME=BINARY [NAME=BINARY ...] > from-rest.csv
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


def run(binary, scene, threads, work):
    prm = open(os.path.join(DATA, scene + ".prm")).read()
    end = float(re.search(r"set End time\s*=\s*(\S+)", prm).group(1))
    out = os.path.join(work, "out")
    prm = re.sub(r"set Output directory\s*=.*", "set Output directory = " + out,
                 prm)
    prm = re.sub(r"set Block file\s*=\s*(\S+)",
                 lambda m: "set Block file = "
                 + os.path.join(DATA, m.group(1)), prm)
    prm = re.sub(r"set Threads\s*=.*", "set Threads = %d" % threads, prm)
    # One output at the start and one at the end, for the settlement.
    prm = re.sub(r"set Output interval\s*=.*", "set Output interval = %g" % end,
                 prm)
    path = os.path.join(work, scene + ".prm")
    open(path, "w").write(prm)
    child = subprocess.Popen([binary, path], stdout=subprocess.DEVNULL)
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
    p.add_argument("binaries", nargs="+")
    a = p.parse_args()
    binaries = [b.split("=", 1) for b in a.binaries]
    w = csv.writer(sys.stdout)
    keys = ["steps", "cuts", "iterations_per_step", "linear_solves",
            "ms_per_step", "time_to_end_s", "peak_memory_MiB",
            "top_settlement_m"]
    w.writerow(["scene", "code", "threads", "runs"] + keys)
    for scene in a.scenes.split(","):
        for threads in [int(t) for t in a.threads.split(",")]:
            results = {name: [] for name, _ in binaries}
            for _ in range(a.repeat):
                for name, binary in binaries:
                    with tempfile.TemporaryDirectory() as work:
                        results[name].append(run(binary, scene, threads,
                                                 work))
            for name, _ in binaries:
                rows = results[name]
                w.writerow([scene, name, threads, len(rows)]
                           + ["%.6g" % statistics.median(r[k] for r in rows)
                              for k in keys])
                sys.stdout.flush()


main()
