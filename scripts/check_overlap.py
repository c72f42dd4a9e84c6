#!/usr/bin/python3
"""Geometric audit of rockdda blocks VTU snapshots (Python standard library):
for each file, the blocks whose polygon is inverted (clockwise, area <= 0) or
self-intersecting, and the deepest penetration of a vertex of one block
inside another (its distance to the other's boundary), also relative to the
smaller block's size (its diameter, as the engine's penetration check) and
to the smaller block's width (area / diameter, what matters for a sliver).

    check_overlap.py out/dda/blocks-00010.vtu [...] [--top N] [--blocks ID,ID]

--blocks restricts the pairs to those involving the given block ids. Used
for the slivers of the layering model DL07 (benchmarks/layering-chapter-3,
README). Exit status 1 if a polygon is inverted or self-intersecting."""
import argparse
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import read_vtu  # noqa: E402


def signed_area(p):
    return 0.5 * sum(p[i][0] * p[(i + 1) % len(p)][1]
                     - p[(i + 1) % len(p)][0] * p[i][1]
                     for i in range(len(p)))


def _orient(p, q, r):
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def _cross(a, b, c, d):
    return (_orient(a, b, c) * _orient(a, b, d) < 0
            and _orient(c, d, a) * _orient(c, d, b) < 0)


def self_intersects(p):
    n = len(p)
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            if _cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]):
                return True
    return False


def _inside(v, poly):
    c = False
    n = len(poly)
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        if (a[1] > v[1]) != (b[1] > v[1]) and \
                v[0] < a[0] + (v[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]):
            c = not c
    return c


def _segment_distance(v, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    t = max(0., min(1., ((v[0] - a[0]) * dx + (v[1] - a[1]) * dy)
                    / (dx * dx + dy * dy)))
    return math.hypot(v[0] - a[0] - t * dx, v[1] - a[1] - t * dy)


def depth(p, q):
    """Deepest vertex of P strictly inside Q (m), 0 if none."""
    d = 0.
    for v in p:
        if _inside(v, q):
            d = max(d, min(_segment_distance(v, q[i], q[(i + 1) % len(q)])
                           for i in range(len(q))))
    return d


def diameter(p):
    m = (sum(v[0] for v in p) / len(p), sum(v[1] for v in p) / len(p))
    return 2. * max(math.dist(m, v) for v in p)


def audit(path, only=None, top=5):
    a = read_vtu.read(path)
    ids = [int(x) for x in a["block_id"].values]
    polys = read_vtu.polygons(a)
    bad = [(ids[i], "inverted" if signed_area(p) <= 0 else "self-intersecting")
           for i, p in enumerate(polys)
           if signed_area(p) <= 0 or self_intersects(p)]
    box = [(min(v[0] for v in p), max(v[0] for v in p),
            min(v[1] for v in p), max(v[1] for v in p)) for p in polys]
    cell = max(1e-9, 2. * sorted(b[1] - b[0] for b in box)[len(box) // 2])
    grid = defaultdict(list)
    for i, b in enumerate(box):
        for gx in range(int(b[0] // cell), int(b[1] // cell) + 1):
            for gy in range(int(b[2] // cell), int(b[3] // cell) + 1):
                grid[(gx, gy)].append(i)
    pairs = set((i, j) for v in grid.values() for i in v for j in v if i < j)
    rows = []
    for i, j in pairs:
        if only and ids[i] not in only and ids[j] not in only:
            continue
        A, B = box[i], box[j]
        if A[1] < B[0] or B[1] < A[0] or A[3] < B[2] or B[3] < A[2]:
            continue
        d = max(depth(polys[i], polys[j]), depth(polys[j], polys[i]))
        if d <= 0.:
            continue
        size = min(diameter(polys[i]), diameter(polys[j]))
        width = min(abs(signed_area(polys[i])) / diameter(polys[i]),
                    abs(signed_area(polys[j])) / diameter(polys[j]))
        rows.append((d / size, d, d / width, ids[i], ids[j]))
    rows.sort(reverse=True)
    print("%s: %d blocks, %s" % (path, len(polys), ", ".join(
        "%d %s" % b for b in bad) or "no inverted or self-intersecting "
        "polygon"))
    for r in rows[:top]:
        print("  blocks %d and %d overlap by %.3g m: %.3g of the smaller "
              "size, %.3g of the smaller width" % (r[3], r[4], r[1], r[0],
                                                   r[2]))
    return not bad


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("files", nargs="+")
    p.add_argument("--top", type=int, default=5)
    p.add_argument("--blocks", help="comma-separated block ids")
    a = p.parse_args()
    only = set(int(x) for x in a.blocks.split(",")) if a.blocks else None
    ok = all([audit(f, only, a.top) for f in a.files])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
