#!/usr/bin/env python3
"""The block's vibration in thesis Fig. 4-2A/B (3D DDA): runs one case with
statistics at every time step and prints, per window of 0.5 s, the mean and
largest number of open contacts (of the block's 4 corners), the largest
strain energy, the range of the block's mean vertical stress sigma_z, the
energy balance at the window's ends (Shi's scheme and the strain damping
only lower it) and the energy the strain damping dissipated.

usage: fig4_2_vibration.py ROCKDDA [--case b] [--blocks FILE] [--dt 0.002]
       [--penalty 1e8] [--strain-damping 0]
"""
import argparse
import csv
import os
import tempfile

from fig4_2_error import PRM, run
import fig4_2_error


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rockdda")
    p.add_argument("--case", default="b")
    p.add_argument("--blocks", default=fig4_2_error.BLOCKS)
    p.add_argument("--dt", default="0.002")
    p.add_argument("--penalty", default="1e8")
    p.add_argument("--strain-damping", default="0")
    p.add_argument("--window", type=float, default=0.5, help="s")
    a = p.parse_args()
    fig4_2_error.BLOCKS = a.blocks
    work = tempfile.mkdtemp(prefix="dda3d-fig4-2-vibration-")
    name = f"vibration-{a.case}"
    run(a.rockdda, os.path.join(PRM, f"dda3d-fig4-2{a.case}.prm"),
        {"Time step": a.dt, "Contact penalty": a.penalty,
         "Strain damping": a.strain_damping, "Statistics interval": a.dt},
        work, name)
    with open(os.path.join(work, name, "statistics.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    print("t0_s open_mean open_max strain_energy_max_J sigma_z_min_Pa "
          "sigma_z_max_Pa balance_start_J balance_end_J damping_J")
    t0 = 0.
    while True:
        w = [r for r in rows if t0 <= r["time_s"] < t0 + a.window]
        if not w:
            break
        op = [r["contacts_open"] for r in w]
        sz = [r["mp1_sigma_z_Pa"] for r in w]
        print(f"{t0:.1f} {sum(op) / len(op):.2f} {max(op):.0f} "
              f"{max(r['strain_energy_J'] for r in w):.3g} {min(sz):.4g} "
              f"{max(sz):.4g} {w[0]['energy_balance_J']:.4g} "
              f"{w[-1]['energy_balance_J']:.4g} "
              f"{w[-1]['damping_dissipation_J']:.4g}")
        t0 += a.window


if __name__ == "__main__":
    main()
