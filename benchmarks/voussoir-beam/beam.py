#!/usr/bin/python3
"""DDA scene of a single jointed roof bed over an opening (Hatzor & Benary
1998, Tel Beer-Sheva: span 7 m, bed 0.5 m thick, vertical joints every
0.25 m): 28 blocks of 0.25 m x 0.5 m between two fixed abutment blocks
(1 m x 1.5 m, faces at x = 0 and x = S), nothing above the bed (the
loosened zone) and the opening below. Material of thesis Table 3-2 (rho
2300 kg/m^3, E 15.3 GPa, nu 0.21, plane strain); every joint has the
friction angle PHI, no cohesion or tension. Measurement points: 1 at the
centre of the block left of midspan, 2 at the centre of the first block
(at the left abutment).

usage: beam.py PHI [--span S] [--thickness T] [--joint-spacing W] > beam.dda
"""
import argparse


def scene(phi, span=7.0, thickness=0.5, spacing=0.25):
    n = int(round(span / spacing))
    if abs(n * spacing - span) > 1e-9 * span:
        raise SystemExit("beam.py: the span must be a multiple of the "
                         "joint spacing")
    lines = ["# Jointed roof bed (Voussoir beam), written by beam.py",
             "material 1 2300 15.3e9 0.21 plane-strain",
             "joint 1 %.10g 0 0" % phi]
    lines.append("block 0 1 1  -1 -0.5  0 -0.5  0 1  -1 1")
    lines.append("block 1 1 1  %.10g -0.5  %.10g -0.5  %.10g 1  %.10g 1"
                 % (span, span + 1, span + 1, span))
    for k in range(n):
        x0, x1 = k * spacing, (k + 1) * spacing
        lines.append("block %d 1 1  %.10g 0  %.10g 0  %.10g %.10g  %.10g %.10g"
                     % (k + 2, x0, x1, x1, thickness, x0, thickness))
    lines += ["fixed-block 0", "fixed-block 1"]
    mid = n // 2 - 1
    lines.append("measure %d %.10g %.10g" % (mid + 2, (mid + 0.5) * spacing,
                                             thickness / 2))
    lines.append("measure 2 %.10g %.10g" % (0.5 * spacing, thickness / 2))
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("phi", type=float, help="friction angle (deg)")
    p.add_argument("--span", type=float, default=7.0)
    p.add_argument("--thickness", type=float, default=0.5)
    p.add_argument("--joint-spacing", type=float, default=0.25)
    a = p.parse_args()
    print(scene(a.phi, a.span, a.thickness, a.joint_spacing), end="")
