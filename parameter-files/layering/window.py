#!/usr/bin/python3
"""Cut a window x0 <= x <= x1 out of a layering block file (boundary check).

usage: window.py BLOCKS.dda X0 X1 > WINDOW.dda

The boundary check of the layering study (issue 16, item 1) compares a
model on the 100 m domain with the same rock mass on a narrower domain.
Cutting the narrow model again with 'cut' would draw other joints (the
generator's random stream depends on the domain), so the check could not
separate the boundary from the realization. This script keeps the wide
model's structure and clips it instead: every block is clipped to the
strip X0 <= x <= X1 (Sutherland-Hodgman against the two vertical lines;
the blocks of the cut are convex or star-shaped bed pieces, and a vertical
line crosses each at most twice); blocks outside are dropped; each kept
edge keeps its joint (edge-joints), a new edge on x = X0 or X1 gets the
boundary joint 1; blocks that touch x = X0 or X1 (within 1 mm) are fixed
like the cut's side blocks, and the cut's fixed blocks stay fixed.
Materials and joints are copied. Block ids are kept."""
import sys

TOL = 1e-3  # m: a block within 1 mm of a window side touches it


def clip(poly, joints, x, keep_greater):
    """Clip polygon (list of (x, y)) with per-edge joints against the
    half-plane x' >= x (keep_greater) or x' <= x. Returns (poly, joints);
    an edge created along the line gets joint 1."""
    inside = (lambda p: p[0] >= x) if keep_greater else (lambda p: p[0] <= x)
    out, out_j = [], []
    n = len(poly)
    for k in range(n):
        a, b, j = poly[k], poly[(k + 1) % n], joints[k]
        ia, ib = inside(a), inside(b)
        if ia:
            out.append(a)
            out_j.append(j if ib else j)
        if ia != ib:
            t = (x - a[0]) / (b[0] - a[0])
            c = (x, a[1] + t * (b[1] - a[1]))
            out.append(c)
            # From a crossing that leaves the half-plane the next edge runs
            # along the line (joint 1); one that enters continues edge j.
            out_j.append(1 if ia else j)
    # Edge k of out runs from out[k] to out[k + 1]; out_j was appended per
    # vertex with the joint of the edge that starts there.
    return out, out_j


def main():
    path, x0, x1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    head, blocks, edge_joints, fixed = [], {}, {}, set()
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "block":
            c = [float(v) for v in w[4:]]
            blocks[int(w[1])] = (w[2], w[3], list(zip(c[0::2], c[1::2])))
        elif w[0] == "edge-joints":
            edge_joints[int(w[1])] = [int(v) for v in w[2:]]
        elif w[0] == "fixed-block":
            fixed.add(int(w[1]))
        elif w[0] in ("material", "joint") or w[0].startswith("#"):
            head.append(line.rstrip("\n"))
        else:
            sys.exit("window.py: %s: unsupported line '%s'" % (path, line.strip()))
    print("# Window %g <= x <= %g m of %s (window.py)" % (x0, x1, path))
    out_fixed = []
    for h in head:
        print(h)
    for b in sorted(blocks):
        mat, joint, poly = blocks[b]
        xs = [p[0] for p in poly]
        if max(xs) <= x0 + 1e-9 or min(xs) >= x1 - 1e-9:
            continue
        js = edge_joints.get(b, [int(joint)] * len(poly))
        poly, js = clip(poly, js, x0, True)
        poly, js = clip(poly, js, x1, False)
        # Drop repeated vertices (a vertex exactly on a line).
        keep = [k for k in range(len(poly))
                if abs(poly[k][0] - poly[k - 1][0]) > 1e-12
                or abs(poly[k][1] - poly[k - 1][1]) > 1e-12]
        js = [js[k] for k in keep]
        poly = [poly[k] for k in keep]
        if len(poly) < 3:
            continue
        print("block %d %s %s  %s" % (b, mat, joint, " ".join(
            "%.17g %.17g" % p for p in poly)))
        print("edge-joints %d %s" % (b, " ".join(str(j) for j in js)))
        xs = [p[0] for p in poly]
        if b in fixed or min(xs) <= x0 + TOL or max(xs) >= x1 - TOL:
            out_fixed.append(b)
    for b in out_fixed:
        print("fixed-block %d" % b)


if __name__ == "__main__":
    main()
