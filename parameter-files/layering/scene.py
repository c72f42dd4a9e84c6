#!/usr/bin/python3
"""Measurement points of the Chapter 3 layering study (thesis Fig. 3-4).

usage: scene.py BLOCKS.dda [--width W] > SCENE.dda

Appends 'measure' lines for points 1-5 to a block file written by 'cut'
for one of the models in this folder. The thesis shows the points on a
vertical line above the centre of the opening, from the immediate roof to
the surface, without coordinates; ours (opening x = W/2 -+ 5 m,
y = 10-16 m, surface at y = 40 m; B = 10 m):

  point 1  y = 16.3 m  immediate roof (0.3 m above it, in the first bed:
                       beds are at least 0.7 m thick)
  point 2  y = 22 m    0.6 B above the roof: just above Terzaghi's
                       loosened zone of 0.5 B, where the thesis finds
                       Voussoir beams
  point 3  y = 27 m    } the rock mass above the roof zone (thesis
  point 4  y = 33 m    } Fig. 3-9 plots points 3, 4, 5)
  point 5  y = 39.7 m  the surface (0.3 m below it, in the top bed)

all at x = W/2 + 0.1 m (off the centre line, so that a point does not fall
on a vertical joint of the symmetric opening). A point on a block edge is
moved 1 cm up (inside one block)."""
import argparse
import sys

POINTS_Y = (16.3, 22.0, 27.0, 33.0, 39.7)


def read_blocks(path):
    """{id: [(x, y), ...]} of the 'block' lines of a DDA block file."""
    blocks = {}
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "block":
                c = [float(v) for v in w[4:]]
                blocks[int(w[1])] = list(zip(c[0::2], c[1::2]))
    return blocks


def inside(poly, x, y):
    """Signed position of (x, y): 1 inside, 0 on an edge (within 1e-9 m),
    -1 outside (even-odd rule)."""
    n = len(poly)
    odd = False
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        dx, dy = x2 - x1, y2 - y1
        ln = (dx * dx + dy * dy) ** 0.5
        if ln > 0:
            t = ((x - x1) * dx + (y - y1) * dy) / (ln * ln)
            if 0 <= t <= 1 and abs((x - x1) * dy - (y - y1) * dx) / ln < 1e-9:
                return 0
        if (y1 > y) != (y2 > y):
            if x < x1 + (y - y1) * dx / dy:
                odd = not odd
    return 1 if odd else -1


def locate(blocks, x, y):
    """The block holding (x, y) strictly inside, moving the point up by
    1 cm at a time (at most 10 times) when it lies on an edge."""
    for _ in range(10):
        for b, poly in blocks.items():
            if inside(poly, x, y) == 1:
                return b, x, y
        y += 0.01
    raise SystemExit("scene.py: no block holds the point (%g, %g)" % (x, y))


def points(blocks, width):
    """[(block, x, y)] of points 1-5."""
    return [locate(blocks, width / 2 + 0.1, y) for y in POINTS_Y]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("blocks")
    p.add_argument("--width", type=float, default=60.0,
                   help="domain width (m), default 60")
    a = p.parse_args()
    text = open(a.blocks).read()
    out = [text.rstrip("\n"), "# measurement points 1-5 (scene.py)"]
    for b, x, y in points(read_blocks(a.blocks), a.width):
        out.append("measure %d %.6f %.6f" % (b, x, y))
    sys.stdout.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
