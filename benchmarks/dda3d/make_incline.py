#!/usr/bin/env python3
"""Write a 3D DDA block file (doc/block-file-format-dda3d.md) of a cubic
block resting on a clamped base slab whose top is a plane of given dip and
dip direction (x east, y north, z up; dip direction clockwise from north).

usage: make_incline.py OUT.blocks [--dip 20] [--dip-direction 90]
       [--friction 30] [--block 1] [--base-length 8] [--base-width 4]
       [--density 1000] [--young 20e6] [--poisson 0.25] [--upslope 2]

The block's bottom face lies on the plane with its centre at the origin
shifted --upslope metres up the dip line; the base (length along the dip
line, width along strike, 1 m thick) is centred on the origin. A measurement
point sits at the block's centroid.
"""
import argparse
import math

p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("--dip", type=float, default=20.)
p.add_argument("--dip-direction", type=float, default=90.)
p.add_argument("--friction", type=float, default=30.)
p.add_argument("--block", type=float, default=1.)
p.add_argument("--base-length", type=float, default=8.)
p.add_argument("--base-width", type=float, default=4.)
p.add_argument("--density", type=float, default=1000.)
p.add_argument("--young", type=float, default=20e6)
p.add_argument("--poisson", type=float, default=0.25)
p.add_argument("--upslope", type=float, default=2.)
a = p.parse_args()

d, b = math.radians(a.dip), math.radians(a.dip_direction)
e1 = (math.sin(b) * math.cos(d), math.cos(b) * math.cos(d), -math.sin(d))
e3 = (math.sin(b) * math.sin(d), math.cos(b) * math.sin(d), math.cos(d))
e2 = (e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
      e3[0] * e1[1] - e3[1] * e1[0])


def world(u, v, w):
    return tuple(u * e1[k] + v * e2[k] + w * e3[k] for k in range(3))


def box(lo, hi):
    return [world(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1],
                  hi[2] if i & 4 else lo[2]) for i in range(8)]


FACES = ["0 2 3 1", "4 5 7 6", "0 1 5 4", "2 6 7 3", "0 4 6 2", "1 3 7 5"]
L, W, s, u0 = a.base_length, a.base_width, a.block, a.upslope
with open(a.out, "w") as f:
    f.write(f"# Block of {s} m on a plane {a.dip}/{a.dip_direction:03.0f}, "
            f"phi = {a.friction} deg (benchmarks/dda3d/make_incline.py)\n")
    f.write(f"material 1 {a.density:.17g} {a.young:.17g} {a.poisson:.17g}\n")
    f.write(f"joint 1 {a.friction:.17g} 0 0\n")
    for bid, lo, hi in ((1, (-L / 2, -W / 2, -1.), (L / 2, W / 2, 0.)),
                        (2, (-u0 - s / 2, -s / 2, 0.), (-u0 + s / 2, s / 2, s))):
        f.write(f"block {bid} 1 1\n")
        for v in box(lo, hi):
            f.write("vertex %.17g %.17g %.17g\n" % v)
        for face in FACES:
            f.write(f"face {face}\n")
    f.write("fixed-block 1\n")
    f.write("measure 2 %.17g %.17g %.17g\n" % world(-u0, 0., s / 2))
