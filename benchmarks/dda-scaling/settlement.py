#!/usr/bin/python3
"""Mean settlement (m) of the top row of blocks between the first and the
last blocks-*.vtu of a rockdda DDA output folder (ASCII VTU, blocks in the
order of the block file). Usage: settlement.py OUTPUT_DIR"""
import glob
import re
import sys


def blocks(path):
    text = open(path).read()

    def array(name):
        m = re.search(r'Name="%s"[^>]*>(.*?)</DataArray>' % name, text, re.S)
        return m.group(1).split()

    pts = re.search(r'<Points>\s*<DataArray[^>]*>(.*?)</DataArray>', text,
                    re.S).group(1).split()
    xy = [(float(pts[i]), float(pts[i + 1])) for i in range(0, len(pts), 3)]
    conn = [int(v) for v in array("connectivity")]
    offsets = [int(v) for v in array("offsets")]
    out, start = [], 0
    for end in offsets:
        out.append([xy[k] for k in conn[start:end]])
        start = end
    return out


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
