#!/usr/bin/python3
"""Voussoir-beam analysis of a jointed roof bed (own implementation).

The iterative Voussoir solution as described by Brady & Brown (2004, Rock
Mechanics for Underground Mining, 3rd ed., sec. 15.2) after Evans (1941),
Beer & Meek (1982) and Sofianos (1996), with the deflection of Diederichs &
Kaiser (1999, Int. J. Rock Mech. Min. Sci. 36, 97-117):

A beam of span S and thickness T under its own weight (unit weight g per
m^3) carries it by a parabolic compression arch between the abutments and
the midspan. The compressive stress is triangular over a depth n T at the
midspan (top) and at the abutments (bottom), so the lever arm of the thrust
is Z0 = T (1 - 2 n / 3) and, by the moment balance of a half-span,

    f_m = g S^2 / (4 n Z),      thrust per metre  H = f_m n T / 2.

The arch (length L = S + 8 Z0^2 / (3 S)) shortens elastically by
dL = f_av L / E, f_av = f_m (2/3 + n) / 2, which lowers its rise to
Z^2 = Z0^2 - 3 S dL / 8 (the parabola's length relation); f_m and Z are
iterated to a fixed point. No real Z (dL too large): snap-through
(buckling). Among the n in (0, 1) with a solution, the equilibrium is the
one with the least f_m (Brady & Brown). The midspan deflection is Z0 - Z.

Sliding at the abutments: the shear force is half the weight, V = g T S / 2,
resisted by H tan(phi), so the friction angle required for stability is

    tan(phi_req) = V / H = g S / (f_m n),

which for a rigid beam (E -> infinity, n = 3/4, Z = T / 2) is 4 Z / S =
2 T / S: independent of the unit weight and of a uniform surcharge (both
scale V and H alike).

With joints (Diederichs & Kaiser's jointed beam, here explicitly): each of
J vertical joints closes by H / k_j under the thrust H (k_j: normal
stiffness per m, e.g. the DDA penalty), which adds J H / k_j to dL.

usage: voussoir.py [--span S] [--thickness T] [--unit-weight G] [--modulus E]
                   [--joints J --joint-stiffness K]
"""
import argparse
import math


def solve_n(span, thickness, unit_weight, modulus, n, joints=0,
            joint_stiffness=math.inf):
    """(f_m, Z, Z0) at load-depth ratio n, or None if the arch snaps
    through (no real Z). JOINTS vertical joints (abutments included) that
    each close by H / JOINT_STIFFNESS (N/m per m) under the thrust H add
    to the arch's shortening."""
    z0 = thickness * (1.0 - 2.0 * n / 3.0)
    length = span + 8.0 * z0 * z0 / (3.0 * span)
    z = z0
    for _ in range(500):
        fm = unit_weight * span * span / (4.0 * n * z)
        fav = fm * (2.0 / 3.0 + n) / 2.0
        thrust = fm * n * thickness / 2.0
        dl = fav * length / modulus + joints * thrust / joint_stiffness
        z2 = z0 * z0 - 3.0 * span * dl / 8.0
        if z2 <= 0.0:
            return None
        znew = math.sqrt(z2)
        if abs(znew - z) < 1e-14 * thickness:
            z = znew
            break
        z = znew
    fm = unit_weight * span * span / (4.0 * n * z)
    return fm, z, z0


def voussoir(span, thickness, unit_weight, modulus, samples=20000, joints=0,
             joint_stiffness=math.inf):
    """The equilibrium of the beam: dict with n, f_m (Pa), Z, deflection (m),
    thrust H (N/m), abutment shear V (N/m) and phi_req (deg); None if it
    snaps through for every n."""
    best = None
    for i in range(1, samples):
        n = i / samples
        s = solve_n(span, thickness, unit_weight, modulus, n, joints,
                    joint_stiffness)
        if s is None:
            continue
        fm, z, z0 = s
        if best is None or fm < best["f_m"]:
            best = {"n": n, "f_m": fm, "Z": z, "Z0": z0,
                    "deflection": z0 - z}
    if best is None:
        return None
    best["thrust"] = best["f_m"] * best["n"] * thickness / 2.0
    best["shear"] = unit_weight * thickness * span / 2.0
    best["phi_req"] = math.degrees(math.atan(best["shear"] / best["thrust"]))
    return best


def main():
    p = argparse.ArgumentParser(description="Voussoir beam: friction angle "
                                "required against abutment sliding")
    p.add_argument("--span", type=float, default=7.0, help="m")
    p.add_argument("--thickness", type=float, default=0.5, help="m")
    p.add_argument("--unit-weight", type=float, default=2300 * 9.80665,
                   help="N/m^3")
    p.add_argument("--modulus", type=float, default=15.3e9, help="Pa")
    p.add_argument("--joints", type=int, default=0,
                   help="number of vertical joints incl. the abutments")
    p.add_argument("--joint-stiffness", type=float, default=math.inf,
                   help="normal stiffness of a joint, N/m per m (e.g. the "
                   "DDA contact penalty)")
    a = p.parse_args()
    r = voussoir(a.span, a.thickness, a.unit_weight, a.modulus,
                 joints=a.joints, joint_stiffness=a.joint_stiffness)
    if r is None:
        print("snap-through: no equilibrium")
        return
    for k in ("n", "f_m", "Z0", "Z", "deflection", "thrust", "shear",
              "phi_req"):
        print("%-10s %.6g" % (k, r[k]))


if __name__ == "__main__":
    main()
