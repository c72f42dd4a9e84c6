#!/usr/bin/python3
"""Write a running-bond brick wall from rest of ROWS x COLUMNS bricks in
rockdda's block-file format, and its parameter file: the scenes of
../shared/data/dda-scenes (wall-25x40, wall-50x80) at any size.

usage: make_wall.py ROWS COLUMNS FOLDER [--end-time T] [--solver S]
                    [--threads N] [--statistics-interval S]

Bricks of 2 m x 1 m (odd rows start and end with a 1 m half brick), a fixed
base 4 m longer than the wall, fixed at four points; rho = 2700 kg/m^3,
E = 10 GPa, nu = 0.25, plane stress, friction 35 deg, no cohesion and no
tensile strength, penalty 1e11 N/m, dt = 1 ms, fully dynamic, gravity on at
t = 0 on unloaded springs. Measurement points on the middle and last brick
of the top row. Writes FOLDER/wall-RxC.blocks and FOLDER/wall-RxC.prm.
"""
import argparse
import os


def write_blocks(path, rows, columns):
    width = 2.0 * columns
    lines = ["# Running-bond brick wall (%d rows x %d bricks, 2 m x 1 m "
             "bricks) on a fixed base (make_wall.py)" % (rows, columns),
             "material 1 2700.0 10000000000.0 0.25 plane-stress",
             "joint 1 35.0 0 0",
             "block 0 1 1 -2.0 -1.0  %r -1.0  %r 0  -2.0 0"
             % (width + 3.0, width + 3.0)]
    n = 1
    top = []
    for r in range(rows):
        y0, y1 = float(r), float(r + 1)
        if r % 2 == 0:
            edges = [2.0 * k for k in range(columns + 1)]
        else:
            edges = [0.0] + [1.0 + 2.0 * k for k in range(columns)] + [width]
        for a, b in zip(edges[:-1], edges[1:]):
            lines.append("block %d 1 1 %r %r  %r %r  %r %r  %r %r"
                         % (n, a, y0, b, y0, b, y1, a, y1))
            if r == rows - 1:
                top.append((n, 0.5 * (a + b), 0.5 * (y0 + y1)))
            n += 1
    for x in (-1.5, width / 3.0, 2.0 * width / 3.0, width + 2.5):
        lines.append("fixed 0 %r -0.5" % x)
    for b, x, y in (top[len(top) // 2 - 1], top[-1]):
        lines.append("measure %d %r %r" % (b, x, y))
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)
    return n


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("rows", type=int)
    p.add_argument("columns", type=int)
    p.add_argument("folder")
    p.add_argument("--end-time", type=float, default=0.003)
    p.add_argument("--solver", default="automatic")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--statistics-interval", type=float, default=0.)
    a = p.parse_args()
    if a.rows < 1 or a.columns < 1:
        raise SystemExit("make_wall.py: ROWS and COLUMNS must be >= 1")
    os.makedirs(a.folder, exist_ok=True)
    name = "wall-%dx%d" % (a.rows, a.columns)
    blocks = write_blocks(os.path.join(a.folder, name + ".blocks"),
                          a.rows, a.columns)
    prm = os.path.join(a.folder, name + ".prm")
    with open(prm + ".tmp", "w") as f:
        f.write("""# Running-bond brick wall on a fixed base, dynamic, from rest
# (make_wall.py: %d blocks)
set Analysis type    = dda
set Output directory = output-%s
subsection DDA
  set Block file          = %s.blocks
  set End time            = %r
  set Time step           = 0.001
  set Dynamic control     = 1
  set Gravity             = 9.80665
  set Contact penalty     = 100000000000.0
  set Shear penalty ratio = 0.4
  set Fixed point penalty = 10000000000000.0
  set Maximum displacement ratio = 0.01
  set Output interval     = 0
  set Statistics interval = %r
  set Maximum open-close iterations = 100
%s  set Threads             = %d
end
""" % (blocks, name, name, a.end_time, a.statistics_interval,
            "" if a.solver == "automatic"
            else "  set Linear solver       = %s\n" % a.solver, a.threads))
    os.replace(prm + ".tmp", prm)
    print(prm)


if __name__ == "__main__":
    main()
