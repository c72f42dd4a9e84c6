#!/usr/bin/python3
"""Mean settlement (m) of the top row of blocks between the first and the
last blocks-*.vtu of a rockdda DDA output folder (ASCII or binary VTU, read
by scripts/read_vtu.py; blocks in the order of the block file). Usage:
settlement.py OUTPUT_DIR"""
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "scripts"))
import read_vtu  # noqa: E402


def blocks(path):
    return read_vtu.polygons(read_vtu.read(path))


def main():
    files = sorted(glob.glob(sys.argv[1] + "/blocks-*.vtu"))
    if len(files) < 2:
        sys.exit("settlement.py: need at least two blocks-*.vtu in "
                 + sys.argv[1])
    first, last = blocks(files[0]), blocks(files[-1])
    top = max(max(y for _, y in b) for b in first)
    rows = [i for i, b in enumerate(first)
            if abs(max(y for _, y in b) - top) < 1e-6 * (1. + abs(top))]
    mean_y = lambda b: sum(y for _, y in b) / len(b)
    s = sum(mean_y(first[i]) - mean_y(last[i]) for i in rows) / len(rows)
    print("%.9e" % s)


main()
