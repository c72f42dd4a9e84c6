#!/usr/bin/python3
"""HDF5 output of dda read back with h5py (issue 16, items 2 and 5), through
the driver. Skipped (exit 77) without python3-h5py (setup.sh installs it).

  study     the layering study's reader (benchmarks/layering-chapter-3/
            study.py, collect()) on a model folder whose DDA wrote
            measurement_points.h5 and statistics.h5 gives the same
            models.csv / timeseries.csv rows as on the same folder without
            them (statistics.h5, then statistics.csv: older runs) and
            without h5py; the stack's bottom block carries the weight above
            it (thesis Table 3-2 reads sigma_x and uy the same way).
  snapshot  every block of the HDF5 snapshots (snapshot-NNNNN.h5, indexed
            by blocks.xdmf / contacts.xdmf) has the vertex count of the
            block file, and the vertices and every field of blocks and
            contacts equal those of the VTU snapshots of the same run
            (scripts/read_vtu.py); the XDMF DataItems name datasets of the
            stated dimensions and the XDMF times equal the files' times;
            the stack's stresses are the weight above each block.

Usage: test_hdf5_output.py DRIVER SOURCE_DIR WORK_DIR study|snapshot"""
import glob
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

driver, source, work = (os.path.abspath(a) for a in sys.argv[1:4])
mode = sys.argv[4]
try:
    import h5py
except ImportError:
    print("python3-h5py is not installed (setup.sh installs it): skipped")
    sys.exit(77)
sys.path.insert(0, os.path.join(source, "scripts"))
sys.path.insert(0, os.path.join(source, "benchmarks", "layering-chapter-3"))

RHO_G = 2700 * 9.80665   # N/m^3 of the blocks below
# Five 1 m blocks stacked on a fixed base (tests/regression/dda_stack.blocks)
# with a point in each; beside them a pentagon and a triangle on the base,
# so that the snapshots hold blocks of 3, 4 and 5 vertices.
BLOCKS = """material 1 2700 1e10 0.25 plane-stress
joint 1 30 0 0
block 0 1 1  -2 -1  3 -1  3 0  -2 0
fixed-block 0
block 1 1 1  0 0  1 0  1 1  0 1
block 2 1 1  0 1  1 1  1 2  0 2
block 3 1 1  0 2  1 2  1 3  0 3
block 4 1 1  0 3  1 3  1 4  0 4
block 5 1 1  0 4  1 4  1 5  0 5
block 6 1 1  -1.6 0  -0.6 0  -0.6 0.6  -1.1 1  -1.6 0.6
block 7 1 1  1.5 0  2.5 0  2 0.8
measure 1 0.5 0.5
measure 2 0.5 1.5
measure 3 0.5 2.5
measure 4 0.5 3.5
measure 5 0.5 4.5
"""
VERTICES = {0: 4, 1: 4, 2: 4, 3: 4, 4: 4, 5: 4, 6: 5, 7: 3}

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run_dda(out, keys):
    """Run dda on BLOCKS (static steps of 0.01 s to 0.2 s) into OUT with the
    extra DDA KEYS."""
    os.makedirs(work, exist_ok=True)
    blocks = os.path.join(work, "scene.blocks")
    open(blocks, "w").write(BLOCKS)
    prm = os.path.join(work, "run.prm")
    open(prm, "w").write(
        "set Analysis type    = dda\nset Output directory = %s\n"
        "subsection DDA\n  set Block file = %s\n  set End time = 0.2\n"
        "  set Time step = 0.01\n  set Dynamic control = 0\n"
        "  set Contact penalty = 1e11\n%send\n"
        % (out, blocks, "".join("  set %s = %s\n" % kv for kv in keys)))
    r = subprocess.run([driver, "--quiet", prm], capture_output=True,
                       text=True, timeout=120)
    if r.returncode != 0:
        sys.exit("driver failed: " + r.stdout + r.stderr)


def study_test():
    import study
    h5 = os.path.join(work, "h5")
    run_dda(os.path.join(h5, "FMML", "dda"),
            [("Output interval", 0), ("Snapshot format", "hdf5"),
             ("Measurement point file", "hdf5")])
    # The same folder without measurement_points.h5, and without any .h5
    # (an older run): statistics.h5, then statistics.csv.
    folders = {"measurement_points.h5": h5}
    for name, drop in (("statistics.h5", ["measurement_points.h5"]),
                       ("statistics.csv", ["measurement_points.h5",
                                           "statistics.h5"])):
        w = os.path.join(work, name.replace(".", "-"))
        shutil.copytree(h5, w)
        for f in drop:
            os.remove(os.path.join(w, "FMML", "dda", f))
        folders[name] = w
    tables = {}
    for name, w in folders.items():
        _, src = study.measurement_rows(os.path.join(w, "FMML", "dda"))
        check(src is not None and os.path.basename(src) == name,
              "%s read from %s" % (name, src))
        tables[name] = study.collect(w, ["FMML"], 0.2)
    # Without h5py the CSV of the same folder.
    real = study.h5py_or_none
    study.h5py_or_none = lambda: None
    _, src = study.measurement_rows(os.path.join(h5, "FMML", "dda"))
    check(os.path.basename(src) == "statistics.csv", "no h5py: " + src)
    tables["no h5py"] = study.collect(h5, ["FMML"], 0.2)
    study.h5py_or_none = real
    ref = tables["statistics.csv"]
    for name, (rows, series) in tables.items():
        check(rows == ref[0], "models.csv row from %s: %s against %s"
              % (name, rows, ref[0]))
        check(series == ref[1], "timeseries.csv from %s" % name)
    rows, series = ref
    # 0.2 s sampled every 0.05 s: 5 times x 5 points.
    check(len(series) == 25, "%d timeseries rows" % len(series))
    check(rows[0]["status"] == "done" and rows[0]["final_time_s"] == "0.2",
          "status %s at %s" % (rows[0]["status"], rows[0]["final_time_s"]))
    # The rows carry the physics: sigma_y of block k (point k) is the
    # weight above its centroid, rho g (5 - k + 1/2) (static, within 1 %
    # as tests/regression/dda_stack.ref), read here from measurement_points.h5
    # directly, as the README shows.
    with h5py.File(os.path.join(h5, "FMML", "dda",
                                "measurement_points.h5"), "r") as f:
        sy = f["sigma_y"][-1]
        check(f["uy"].attrs["unit"] in ("m", b"m"), "unit of uy")
        check(tuple(f["initial_position"][4]) == (0.5, 4.5),
              "point 5 at %s" % (f["initial_position"][4],))
    for k in range(1, 6):
        exact = -RHO_G * (5 - k + 0.5)
        check(abs(sy[k - 1] - exact) < 0.01 * abs(exact),
              "point %d: sigma_y %g Pa, weight %g Pa" % (k, sy[k - 1], exact))
    print("study.py: models.csv and timeseries.csv (%d rows) equal from "
          "measurement_points.h5, statistics.h5 and statistics.csv"
          % len(series))


def datasets(xdmf):
    """(dims, file, path) of every DataItem of an XDMF index, and the times
    with the file of each grid."""
    root = ET.parse(xdmf).getroot()
    items, times = [], []
    for grid in root.iter("Grid"):
        t = grid.find("Time")
        if t is None:
            continue
        files = set()
        for item in grid.iter("DataItem"):
            f, path = item.text.strip().split(":")
            items.append(([int(d) for d in item.get("Dimensions").split()],
                          f, path))
            files.add(f)
        check(len(files) == 1, "one file per grid: %s" % files)
        times.append((float(t.get("Value")), files.pop()))
    return items, times


def cells(group):
    """Per cell its list of point indices, from /topology and /offsets of a
    snapshot group (blocks: mixed polygons 3, n, i..; contacts: pairs)."""
    top = group["topology"][:]
    offsets = group["offsets"][:]
    if top.ndim == 2:
        return [list(c) for c in top]
    out, at, start = [], 0, 0
    for end in offsets:
        check(top[at] == 3 and top[at + 1] == end - start,
              "polygon at %d: type %d, %d points" % (at, top[at], top[at + 1]))
        out.append(list(top[at + 2:at + 2 + top[at + 1]]))
        at += 2 + top[at + 1]
        start = end
    check(at == len(top), "topology fully used")
    return out


def snapshot_test():
    import read_vtu
    vtu_out = os.path.join(work, "vtu")
    h5_out = os.path.join(work, "hdf5")
    for out, fmt in ((vtu_out, "vtu"), (h5_out, "hdf5")):
        shutil.rmtree(out, ignore_errors=True)
        run_dda(out, [("Output interval", 0.1), ("Snapshot format", fmt)])
    snaps = sorted(glob.glob(h5_out + "/snapshot-*.h5"))
    check(len(snaps) == 3, "%d snapshots at 0, 0.1, 0.2 s" % len(snaps))
    for index in ("blocks.xdmf", "contacts.xdmf"):
        items, times = datasets(os.path.join(h5_out, index))
        check([os.path.join(h5_out, f) for _, f in times] == snaps,
              index + " lists the snapshots")
        for t, f in times:
            with h5py.File(os.path.join(h5_out, f), "r") as h:
                check(abs(h.attrs["time"] - t) <= 1e-12, "time of " + f)
        for dims, f, path in items:
            with h5py.File(os.path.join(h5_out, f), "r") as h:
                check(path in h and list(h[path].shape) == dims,
                      "%s: %s:%s %s" % (index, f, path, dims))
    n_fields = 0
    for k, snap in enumerate(snaps):
        with h5py.File(snap, "r") as h:
            for group, prefix in (("blocks", "blocks"),
                                  ("contacts", "contacts")):
                vtu = read_vtu.read(os.path.join(
                    vtu_out, "%s-%05d.vtu" % (prefix, k)))
                g = h[group]
                pts = g["points"][:]
                got = [[tuple(pts[i]) for i in c] for c in cells(g)]
                want = [[tuple(p) for p in c] for c in
                        _vtu_cells(vtu)]
                check(got == want, "%s of %s: vertices" % (group, snap))
                fields = [n for n in g if n not in
                          ("points", "topology", "offsets")]
                for n in fields:
                    a = g[n][:]
                    v = vtu[n]
                    flat = [x for x in a.reshape(-1).tolist()]
                    check(flat == list(v.values)
                          and (1 if a.ndim == 1 else a.shape[1])
                          == v.components,
                          "%s/%s of %s equals the VTU" % (group, n, snap))
                    n_fields += 1
                check(sorted(fields) == sorted(
                    n for n in vtu if n not in ("Points", "connectivity",
                                                "offsets", "types")),
                      "%s of %s: the fields of the VTU (%s)"
                      % (group, snap, fields))
                if group == "blocks":
                    ids = g["block_id"][:].tolist()
                    check([len(c) for c in got]
                          == [VERTICES[i] for i in ids],
                          "vertex counts %s of blocks %s"
                          % ([len(c) for c in got], ids))
                    if k == len(snaps) - 1:
                        s = g["stress"][:]
                        for b in range(1, 6):
                            exact = -RHO_G * (5 - b + 0.5)
                            sy = s[ids.index(b)][1]
                            check(abs(sy - exact) < 0.01 * abs(exact),
                                  "block %d: sigma_yy %g Pa, weight %g Pa"
                                  % (b, sy, exact))
    print("HDF5 snapshots: %d files, %d fields equal to the VTU, every "
          "block's vertices intact" % (len(snaps), n_fields))


def _vtu_cells(arrays):
    """Per cell its points (x, y, z) from a VTU read by read_vtu."""
    import read_vtu  # noqa: F401
    pts = arrays["Points"].tuples()
    conn = arrays["connectivity"].values
    out, start = [], 0
    for end in arrays["offsets"].values:
        out.append([tuple(pts[i]) for i in conn[start:end]])
        start = end
    return out


shutil.rmtree(work, ignore_errors=True)
{"study": study_test, "snapshot": snapshot_test}[mode]()
if failures:
    sys.exit("%d failure(s)" % len(failures))
