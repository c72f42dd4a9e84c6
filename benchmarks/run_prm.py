"""Helpers of the results scripts of the benchmarks that use
benchmarks/run_prm.sh (seismic-block1, seismic-compare): read a run's CSV
tables and summary, collect failed checks, write results.md.

Imported by the heredoc Python of run.sh with
    sys.path.insert(0, os.path.join(os.environ["ROCKDDA_BENCHMARKS"]))
(run_prm.sh exports ROCKDDA_BENCHMARKS, the benchmarks folder).
"""
import csv
import os
import sys


def table(out, name):
    """Rows of OUT/NAME as dicts of floats, keyed by the header."""
    with open(os.path.join(out, name)) as f:
        rows = list(csv.reader(f))
    return [dict(zip(rows[0], map(float, r))) for r in rows[1:]]


def summary(out):
    """OUT/summary.csv as {quantity: value string}."""
    with open(os.path.join(out, "summary.csv")) as f:
        return {r[0]: r[1] for r in csv.reader(f)}


class Checks:
    """Failed checks are printed and make finish() exit 1."""

    def __init__(self):
        self.ok = True

    def __call__(self, condition, what):
        if not condition:
            self.ok = False
            print("check failed:", what)


def finish(md, lines, checks):
    """Write LINES to MD, print them, exit 0 if every check passed."""
    with open(md, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    sys.exit(0 if checks.ok else 1)
