#!/usr/bin/python3
"""ParaView output of dda (issue 11, item 7), through the driver: a block
(material 5) on a block (material 9) on a fixed base, static steps with VTU
snapshots. The VTUs are binary (no ASCII DataArray, zlib-compressed), the
blocks' material is the block file's id, the contacts carry the two block
ids, a negative gap, force = penalty x penetration and the state locked;
scripts/read_vtu.py reads them and benchmarks/dda-scaling/settlement.py
works on them.

Usage: test_read_vtu.py DRIVER SOURCE_DIR WORK_DIR"""
import glob
import os
import shutil
import subprocess
import sys

driver, source, work = (os.path.abspath(a) for a in sys.argv[1:4])
sys.path.insert(0, os.path.join(source, "scripts"))
import read_vtu  # noqa: E402

PENALTY = 1e11
BLOCKS = """# two blocks on a fixed base; material ids that are not indices
material 9 2700 1e10 0.25 plane-stress
material 5 2500 1e10 0.25 plane-stress
joint 1 30 0 0
block 100 9 1  -1 -1  2 -1  2 0  -1 0
fixed-block 100
block 200 9 1  0 0  1 0  1 1  0 1
block 300 5 1  0 1  1 1  1 2  0 2
"""
PRM = """set Analysis type    = dda
set Output directory = output
subsection DDA
  set Block file      = scene.blocks
  set End time        = 0.1
  set Time step       = 0.01
  set Dynamic control = 0
  set Contact penalty = %g
  set Output interval = 0.05
end
""" % PENALTY

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
open(os.path.join(work, "scene.blocks"), "w").write(BLOCKS)
open(os.path.join(work, "scene.prm"), "w").write(PRM)
run = subprocess.run([driver, "scene.prm"], cwd=work, capture_output=True,
                     text=True, timeout=120)
if run.returncode != 0:
    sys.exit("driver failed: " + run.stdout + run.stderr)
out = os.path.join(work, "output")
blocks = sorted(glob.glob(out + "/blocks-*.vtu"))
contacts = sorted(glob.glob(out + "/contacts-*.vtu"))
check(len(blocks) >= 2 and len(contacts) == len(blocks), "VTU series")

for f in blocks + contacts:
    text = open(f).read()
    check('format="ascii"' not in text, f + " has ASCII arrays")
    check('compressor="vtkZLibDataCompressor"' in text, f + " not compressed")

b = read_vtu.read(blocks[-1])
check(b["block_id"].values == [100, 200, 300], "block ids %s"
      % b["block_id"].values)
check(b["material"].values == [9, 9, 5], "material ids %s"
      % b["material"].values)
check(b["stress"].components == 6
      and b["stress"].attributes.get("ComponentName3") == "XY",
      "stress is a symmetric tensor")
# Block 200 carries block 300: sigma_yy < 0; no out-of-plane components.
s200 = b["stress"].tuples()[1]
check(s200[1] < 0. and s200[2] == s200[4] == s200[5] == 0., "stress %s"
      % (s200,))
check(len(read_vtu.polygons(b)) == 3, "three polygons")

c = read_vtu.read(contacts[-1])
pairs = list(zip(c["vertex_block"].values, c["edge_block"].values))
check(len(pairs) > 0, "contacts")
on_base = 0
for k, (i, j) in enumerate(pairs):
    check((min(i, j), max(i, j)) in ((100, 200), (200, 300)),
          "contact %d between %d and %d" % (k, i, j))
    if c["state"].values[k] == 0:
        continue
    gap = c["normal_gap"].values[k]
    force = c["normal_force"].values[k]
    check(c["state"].values[k] == 2, "closed contact %d locked" % k)
    check(gap < 0. and force > 0., "contact %d compressed" % k)
    check(abs(-gap * PENALTY - force) < 1e-3 * force,
          "contact %d: force %g, penalty x penetration %g"
          % (k, force, -gap * PENALTY))
    on_base += (i, j) == (200, 100)
check(on_base == 2, "both corners of block 200 on the base")

settle = subprocess.run(
    [sys.executable,
     os.path.join(source, "benchmarks", "dda-scaling", "settlement.py"), out],
    capture_output=True, text=True)
check(settle.returncode == 0, "settlement.py: " + settle.stderr)
if settle.returncode == 0:
    s = float(settle.stdout)
    check(0. <= s < 1e-5, "settlement %g m" % s)

if failures:
    sys.exit("%d failure(s)" % len(failures))
print("read_vtu: %d block and contact files checked" % (2 * len(blocks)))
