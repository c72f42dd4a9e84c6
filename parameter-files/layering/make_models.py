#!/usr/bin/python3
"""Writes the 16 structure files of the Chapter 3 layering study (thesis
Table 3-1) and the wide-domain check model into this folder:

  FMML.prm            mechanically layered model (FSI 1.3, beds >= 0.7 m)
  DL01.prm ... DL15.prm   the same bed sequence, through-going bedding
                      planes and one vertical Shi & Goodman joint set
                      (L = 5, 10, 15 m; b = L/5 ... L; s = 0.54 m; DR 0.5)
  FMML-wide.prm       FMML on a 100 m wide domain (boundary check)
  FMML-seed2.prm      FMML with random seed 2 (another realization, to
                      tell the boundary's effect from the realization's)

Each is a 'cut' analysis that writes blocks.dda with the bottom and side
blocks fixed; table-3-2.prm holds the DDA controls of thesis Table 3-2 and
scene.py adds the measurement points 1-5. Run: python3 make_models.py"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))

TEMPLATE = """# Thesis Chapter 3.4 layering study, model {name}{what}
# Outline (assumed, thesis Fig. 3-4 gives no numbers): {width} m x 40 m
# section, opening B = 10 m wide and 6 m high at x = {x0}-{x1} m,
# y = 10-16 m; bottom and side blocks fixed. Written by make_models.py.
#   rockdda parameter-files/layering/{name}.prm   (cut: blocks.dda)
# then scene.py adds the measurement points and table-3-2.prm runs DDA
# (benchmarks/layering-chapter-3/run.sh does all of it).
set Analysis type    = cut
set Output directory = output-layering-{name}

subsection Structure
  set Domain      = 0, 0; {width}, 0; {width}, 40; 0, 40
  set Excavations = {x0}, 10; {x1}, 10; {x1}, 16; {x0}, 16
  set Random seed = {seed}
  subsection Bedding
    set Enabled                   = true
    set Thickness log10 mean      = 0
    set Thickness log10 deviation = -0.2
    set Minimum thickness         = 0.7
    set Confined joints           = {confined}
    set Fracture spacing index    = 1.3
  end
  subsection Joint set 1
    set Enabled              = {dl}
    set Dip                  = 90
    set Mean length          = {L}
    set Mean bridge          = {b}
    set Mean spacing         = 0.54
    set Degree of randomness = 0.5
  end
  subsection Cutting
    set Sliver area = 1e-3
  end
end

subsection Cut
  set Plots                    = false
  set Write traces             = false
  set Fixed blocks             = bottom-and-sides
  set Write DDA parameter file = false
end
"""


def models():
    """(name, L, b) of the 16 models of Table 3-1 (L = b = 0 for FMML)."""
    out = [("FMML", 0, 0)]
    k = 1
    for length in (5, 10, 15):
        for i in range(1, 6):
            out.append(("DL%02d" % k, length, length // 5 * i))
            k += 1
    return out


def write(name, length, bridge, width=60, seed=1):
    x0 = (width - 10) // 2
    dl = length > 0
    what = (": L = %d m, b = %d m (Table 3-1 model %d)"
            % (length, bridge, int(name[2:])) if dl else
            ": mechanically layered (FSI 1.3, beds >= 0.7 m)")
    text = TEMPLATE.format(name=name, what=what, width=width, x0=x0,
                           x1=x0 + 10, confined="false" if dl else "true",
                           dl="true" if dl else "false",
                           L=length if dl else 5, b=bridge if dl else 1,
                           seed=seed)
    with open(os.path.join(HERE, name + ".prm"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    for name, length, bridge in models():
        write(name, length, bridge)
    write("FMML-wide", 0, 0, width=100)
    write("FMML-seed2", 0, 0, seed=2)
