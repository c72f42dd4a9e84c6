#!/usr/bin/python3
"""Time per step against N on walls released from rest, 10^3 to 10^6
blocks, through the rockdda driver (make_wall.py scenes: the bricks,
material and controls of ../shared/data/dda-scenes).

usage: scaling_from_rest.py ROCKDDA [--sizes 25x40,50x80,...] [--steps 3]
                            [--threads 2] [--repeat 3] [--work DIR]
                            > scaling-from-rest.csv

Each wall runs STEPS steps of 1 ms from rest (no snapshots, statistics at
the end only), REPEAT times (sizes alternating within a round); one CSV
row per size with the medians of the driver's wall time (which includes
reading the block file and the first contact detection), ms per step,
open-close iterations per step, CG iterations per step and the peak
resident memory. The last row fits time per step ~ N^a by least squares
over the sizes.
"""
import argparse
import csv
import math
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def summary(path):
    out = {}
    with open(path) as f:
        for row in csv.reader(f):
            if len(row) >= 2:
                out[row[0]] = row[1]
    return out


def run(rockdda, prm):
    child = subprocess.Popen([rockdda, "--quiet", prm],
                             stdout=subprocess.DEVNULL,
                             cwd=os.path.dirname(prm))
    _, status, usage = os.wait4(child.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("scaling_from_rest.py: %s failed" % prm)
    name = os.path.splitext(os.path.basename(prm))[0]
    s = summary(os.path.join(os.path.dirname(prm), "output-" + name,
                             "summary.csv"))
    steps = float(s["steps"])
    return {"wall_s": float(s["wall_time"]),
            "ms_per_step": 1e3 * float(s["wall_time"]) / steps,
            "open_close_per_step": float(s["open_close_iterations_per_step"]),
            "cg_per_step": float(s["solver_iterations"]) / steps,
            "cuts": float(s["time_step_cuts"]),
            "peak_MiB": usage.ru_maxrss / 1024.}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("--sizes",
                   default="25x40,50x80,100x100,200x200,250x400,1000x1000")
    p.add_argument("--steps", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--work", default="/tmp/rockdda-scaling-from-rest")
    a = p.parse_args()
    rockdda = os.path.abspath(a.rockdda)
    prms, blocks = [], []
    for size in a.sizes.split(","):
        rows, columns = (int(v) for v in size.split("x"))
        prm = subprocess.run(
            [sys.executable, os.path.join(HERE, "make_wall.py"), str(rows),
             str(columns), a.work, "--end-time", repr(a.steps * 1e-3),
             "--threads", str(a.threads),
             "--statistics-interval", repr(a.steps * 1e-3)],
            check=True, capture_output=True, text=True).stdout.strip()
        prms.append(prm)
        with open(prm.replace(".prm", ".blocks")) as f:
            blocks.append(sum(1 for line in f if line.startswith("block ")))
    results = [[] for _ in prms]
    for _ in range(a.repeat):
        for k, prm in enumerate(prms):
            results[k].append(run(rockdda, prm))
    w = csv.writer(sys.stdout)
    keys = ["wall_s", "ms_per_step", "open_close_per_step", "cg_per_step",
            "cuts", "peak_MiB"]
    w.writerow(["blocks", "threads", "steps", "runs"] + keys)
    med = []
    for n, rows in zip(blocks, results):
        m = {k: statistics.median(r[k] for r in rows) for k in keys}
        med.append(m)
        w.writerow([n, a.threads, a.steps, len(rows)]
                   + ["%.6g" % m[k] for k in keys])
    if len(blocks) > 1:
        x = [math.log(n) for n in blocks]
        for key in ("ms_per_step",):
            y = [math.log(m[key]) for m in med]
            xm, ym = sum(x) / len(x), sum(y) / len(y)
            slope = sum((u - xm) * (v - ym) for u, v in zip(x, y)) / \
                sum((u - xm) ** 2 for u in x)
            w.writerow(["exponent_%s" % key, "%.3f" % slope])
            y = [math.log(m["ms_per_step"] / m["open_close_per_step"])
                 for m in med]
            ym = sum(y) / len(y)
            slope = sum((u - xm) * (v - ym) for u, v in zip(x, y)) / \
                sum((u - xm) ** 2 for u in x)
            w.writerow(["exponent_ms_per_open_close_iteration",
                        "%.3f" % slope])


if __name__ == "__main__":
    main()
