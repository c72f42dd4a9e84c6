#!/usr/bin/python3
"""Layering study of thesis Chapter 3.4-3.5 (issue 16, items 1 and 2).

usage: study.py ROCKDDA [--end-time T] [--jobs J] [--models NAME ...]
                [--seeds N] [--runs NAME-sK ...] [--merge SEEDS_CSV]
                [--set KEY=VALUE ...]
                [--work FOLDER] [--timeout S] [--retry-failed]
                [--out DIR] [--collect-only]

Runs the 16 models of thesis Table 3-1 (parameter-files/layering: FMML and
DL01-DL15, and with --models also FMML-wide, the boundary check) through
'cut' (blocks.dda), scene.py (measurement points 1-5) and 'dda' with the
controls of Table 3-2 (parameter-files/layering/table-3-2.prm), J models at
a time (default 2, each on one solver thread), and writes into DIR (default:
this folder):

  models.csv        one row per model: status (done / failed / stopped),
                    the engine's diagnosis of a failed run, blocks, steps,
                    cuts, wall time, wall time per step and per block-step,
                    final vertical displacement and horizontal stress at
                    points 1-5, the loosened-zone height / B
  timeseries.csv    vertical displacement and horizontal stress at points
                    1-5 against time (every 0.05 s; thesis Fig. 3-7C/D)
  results.md        the tables
  fig-3-7.png       FMML: displacement and horizontal compressive stress
                    of points 1-5 against time
  fig-3-9.png       final displacement of points 3, 4, 5 against b/L for
                    each L, FMML for reference
  deformed-*.png    the deformed roof zone of FMML, DL02, DL07 (Fig. 3-8)

With --seeds N each model also runs on the realizations of random seeds 2
.. N of its structure ('Random seed' of its cut; model folder NAME-sK),
the tables above stay those of seed 1, and

  seeds.csv         one row per model and seed (the columns of models.csv)
  seeds.md          per model: mean, smallest and largest over the seeds of
                    the final vertical displacement at points 3-5 and of
                    the loosened-zone height / B
  fig-3-9-seeds.png Fig. 3-9 with the mean over the seeds and the range

--runs NAME-sK ... runs only those model folders (e.g. the realizations a
first pass reported failed; with --models also those models) and writes
only seeds.csv, seeds.md and fig-3-9-seeds.png for them. --merge SEEDS_CSV
adds the rows of an earlier seeds.csv that the runs do not replace, in its
order (a run that completed under the default limits is the same run
under looser ones). --set KEY=VALUE (repeatable) overrides a key of the
DDA section of table-3-2.prm in every run (e.g. --set "Penetration
limit=0.05" or --set "Contact penalty=1e9"): give such runs their own
--work and --out, as a model's checkpoint holds the values it ran with.

Each model's DDA also writes WORK/NAME/dda/measurement_points.h5, the
time series of points 1-5 in HDF5 (time; ux, uy, sigma_x, sigma_y, tau_xy
per point: every row of its statistics.csv, i.e. every 0.01 s; layout in
README.md), rewritten atomically at each checkpoint. The tables and plots
read the time series from it (with python3-h5py), else from statistics.h5,
else from statistics.csv (older runs, or no h5py): the same tables, as the
values are printed as the CSV prints them (measurement_rows()).

Each model runs in WORK/NAME (default WORK = ./runs beside ROCKDDA's build
folder) from a copy of ROCKDDA made once (WORK/rockdda), with checkpoints
every 0.1 s: running the study again skips the finished models and resumes
the others from their checkpoints (bit for bit, so a killed study produces
the same tables); a larger --end-time extends finished models. SIGINT /
SIGTERM stop the running models with a checkpoint. A model that fails (the
engine's diagnosis in its log.txt, e.g. the time step cut below its
minimum) is marked failed with the diagnosis and the rest goes on; it is
rerun only with --retry-failed. --timeout stops a model after S s of wall
time (checkpoint written; status 'stopped', resumable).

Exit status 0 when every model reached the end time, 1 otherwise.
"""
import argparse
import concurrent.futures
import csv
import fcntl
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
LAYERING = os.path.join(SOURCE, "parameter-files", "layering")
sys.path.insert(0, LAYERING)
sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import make_models  # noqa: E402
import scene  # noqa: E402
import read_vtu  # noqa: E402

B = 10.0            # opening width (m)
ROOF_Y = 16.0       # roof level (m)
LOOSE_THRESHOLDS = (0.05, 0.1, 0.2)   # downward displacement (m)
STOP = threading.Event()
RUNNING = {}
RUNNING_LOCK = threading.Lock()


def split_seed(name):
    """(base model name, seed) of a model folder name: NAME-sK is model
    NAME on the realization of random seed K; NAME is seed 1."""
    m = re.fullmatch(r"(.+)-s(\d+)", name)
    return (m.group(1), int(m.group(2))) if m else (name, 1)


def model_list():
    """[(name, L, b)] of Table 3-1 (FMML: L = b = 0), as make_models.py
    writes them."""
    return make_models.models()


def set_key(text, key, value):
    """TEXT with 'set KEY = ...' replaced by VALUE (the key must exist)."""
    lines = text.split("\n")
    for i, line in enumerate(lines):
        w = line.split("=", 1)
        if len(w) == 2 and w[0].split() == ["set"] + key.split():
            lines[i] = w[0] + "= " + value
            return "\n".join(lines)
    raise SystemExit("study.py: no key '%s'" % key)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


SERIES_FIELDS = {"ux": "m", "uy": "m", "sigma_x": "Pa", "sigma_y": "Pa",
                 "tau_xy": "Pa"}


def h5py_or_none():
    """The h5py module (Debian python3-h5py, installed by setup.sh), or
    None without it (the CSV is read then)."""
    try:
        import h5py
        return h5py
    except ImportError:
        return None


def number(v):
    """V as statistics.csv prints it (io::format_number: 12 significant
    digits, C++'s %g), so that the tables from HDF5 equal those from the
    CSV character for character."""
    return "%.12g" % v


def measurement_rows(out):
    """(rows, source) of the time series of a model's DDA output folder
    OUT: one dict per row of statistics.csv with the CSV's column names
    (time_s, mpK_ux_m, mpK_uy_m, mpK_sigma_x_Pa, mpK_sigma_y_Pa,
    mpK_tau_xy_Pa for each point K) and the values as the CSV prints them;
    SOURCE the file read. Reads measurement_points.h5 (Measurement point
    file = hdf5), else statistics.h5 (Snapshot format = hdf5), when h5py is
    there, else statistics.csv (older runs); ([], None) without any."""
    h5py = h5py_or_none()
    mp = os.path.join(out, "measurement_points.h5")
    if h5py and os.path.exists(mp):
        with h5py.File(mp, "r") as f:
            time_s = f["time"][:]
            # rows x points (1-D for one point).
            data = {q: f[q][:].reshape(len(time_s), -1)
                    for q in SERIES_FIELDS}
        rows = []
        for i, t in enumerate(time_s):
            r = {"time_s": number(t)}
            for q, unit in SERIES_FIELDS.items():
                for k, v in enumerate(data[q][i], 1):
                    r["mp%d_%s_%s" % (k, q, unit)] = number(v)
            rows.append(r)
        return rows, mp
    st = os.path.join(out, "statistics.h5")
    if h5py and os.path.exists(st):
        with h5py.File(st, "r") as f:
            # The datasets in the order written (the CSV's), named as the
            # CSV's header names them (io::Table::add_column).
            names = []
            f.id.links.iterate(lambda n: names.append(n.decode()),
                               idx_type=h5py.h5.INDEX_CRT_ORDER)
            cols = []
            for n in names:
                unit = f[n].attrs["unit"]
                unit = unit.decode() if isinstance(unit, bytes) else unit
                head = n if unit == "-" else \
                    n + "_" + unit.replace("/", "_").replace("^", "p")
                cols.append((head, f[n][:]))
        return [{c: number(v[i]) for c, v in cols}
                for i in range(len(cols[0][1]) if cols else 0)], st
    csv_path = os.path.join(out, "statistics.csv")
    if os.path.exists(csv_path):
        return read_csv(csv_path), csv_path
    return [], None


def summary(path):
    """{key: value string} of a summary.csv (key,value,unit rows)."""
    out = {}
    if os.path.exists(path):
        with open(path) as f:
            for row in csv.reader(f):
                if len(row) >= 2:
                    out[row[0]] = row[1]
    return out


def run(cmd, log, timeout=None):
    """Runs CMD (stdout/stderr to LOG) in its own process group; returns
    (exit code, 'stopped' if stopped by STOP or the timeout)."""
    with open(log, "a") as out:
        p = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT,
                             start_new_session=True)
        with RUNNING_LOCK:
            RUNNING[p.pid] = p
        start = time.time()
        stopped = None
        try:
            while p.poll() is None:
                if STOP.is_set() or (timeout and time.time() - start > timeout):
                    stopped = "stopped"
                    p.send_signal(signal.SIGTERM)
                    try:
                        p.wait(120)
                    except subprocess.TimeoutExpired:
                        p.kill()
                    break
                time.sleep(0.2)
        finally:
            with RUNNING_LOCK:
                RUNNING.pop(p.pid, None)
        return p.wait(), stopped


def diagnosis(folder):
    """The engine's reason a run failed (log.txt 'DDA stopped: ...' or the
    driver's error line), else ''."""
    for name in ("log.txt", "driver.log"):
        path = os.path.join(folder, name)
        if os.path.exists(path):
            for line in open(path, errors="replace"):
                for tag in ("DDA stopped: ", "rockdda: error: "):
                    if tag in line:
                        return line.split(tag, 1)[1].strip()
    return ""


def run_model(rockdda, work, name, end_time, timeout, retry_failed, jobs,
              overrides=None):
    """Cut, measurement points and DDA of one model, resumed if possible,
    while holding the model's lock (another study process running the same
    folder skips it); OVERRIDES {key: value} replace keys of the DDA
    section of table-3-2.prm. Returns a dict with its status."""
    folder = os.path.join(work, name)
    os.makedirs(folder, exist_ok=True)
    if STOP.is_set():
        return {"status": "stopped", "diagnosis": "not started (stopped)"}
    with open(os.path.join(folder, "lock"), "w") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            return {"status": "stopped",
                    "diagnosis": "busy: another study process runs it"}
        return run_model_locked(rockdda, folder, name, end_time, timeout,
                                retry_failed, jobs, overrides or {})


def prepare_model(rockdda, folder, name):
    """Cut the blocks of model NAME into FOLDER/cut and write
    FOLDER/scene.dda with the measurement points 1-5 (each once). Returns
    None, or the diagnosis of a failed cut."""
    # 1. cut (once).
    blocks = os.path.join(folder, "cut", "blocks.dda")
    if not os.path.exists(blocks):
        base, seed = split_seed(name)
        text = open(os.path.join(LAYERING, base + ".prm")).read()
        text = set_key(text, "Output directory", os.path.join(folder, "cut"))
        if seed != 1:
            text = set_key(text, "Random seed", str(seed))
        prm = os.path.join(folder, "cut.prm")
        with open(prm, "w") as f:
            f.write(text)
        rc, _ = run([rockdda, "--quiet", prm],
                    os.path.join(folder, "driver.log"))
        if rc != 0:
            return diagnosis(os.path.join(folder, "cut")) or "cut failed"
    # 2. measurement points.
    scene_file = os.path.join(folder, "scene.dda")
    if not os.path.exists(scene_file):
        width = 100.0 if name.endswith("-wide") else 60.0
        pts = scene.points(scene.read_blocks(blocks), width)
        text = open(blocks).read().rstrip("\n")
        text += "\n# measurement points 1-5 (scene.py)\n"
        text += "".join("measure %d %.6f %.6f\n" % p for p in pts)
        with open(scene_file + ".tmp", "w") as f:
            f.write(text)
        os.replace(scene_file + ".tmp", scene_file)
    return None


def run_model_locked(rockdda, folder, name, end_time, timeout, retry_failed,
                     jobs, overrides):
    failed_marker = os.path.join(folder, "FAILED")
    if os.path.exists(failed_marker) and not retry_failed:
        return {"status": "failed", "diagnosis": open(failed_marker).read()
                .strip()}
    if os.path.exists(failed_marker):
        os.remove(failed_marker)
    d = prepare_model(rockdda, folder, name)
    if d is not None:
        with open(failed_marker, "w") as f:
            f.write(d + "\n")
        return {"status": "failed", "diagnosis": d}
    # 3. DDA, resumed from the checkpoint when there is one.
    scene_file = os.path.join(folder, "scene.dda")
    out = os.path.join(folder, "dda")
    s = summary(os.path.join(out, "summary.csv"))
    if s.get("completed") == "1" and \
            float(s.get("final_time", 0)) >= end_time - 1e-9:
        return {"status": "done"}
    resume = os.path.exists(os.path.join(out, "checkpoint.bin"))
    text = open(os.path.join(LAYERING, "table-3-2.prm")).read()
    text = set_key(text, "Output directory", out)
    text = set_key(text, "Block file", scene_file)
    text = set_key(text, "End time", repr(end_time))
    text = set_key(text, "Resume", "true" if resume else "false")
    extra = {"Threads": 1 if jobs > 1 else 0}
    for key, value in overrides.items():
        if re.search(r"^\s*set\s+%s\s*=" % re.escape(key), text, re.M):
            text = set_key(text, key, str(value))
        else:
            extra[key] = value
    text += "\nsubsection DDA\n%send\n" % "".join(
        "  set %s = %s\n" % kv for kv in extra.items())
    prm = os.path.join(folder, "dda.prm")
    with open(prm, "w") as f:
        f.write(text)
    start = time.time()
    rc, stopped = run([rockdda, "--quiet", prm],
                      os.path.join(folder, "driver.log"), timeout)
    with open(os.path.join(folder, "wall.csv"), "a") as f:
        f.write("%.3f,%.3f\n" % (start, time.time() - start))
    s = summary(os.path.join(out, "summary.csv"))
    if stopped or s.get("completed") == "0":
        return {"status": "stopped"}
    if rc != 0:
        d = diagnosis(out) or diagnosis(folder) or "exit code %d" % rc
        with open(failed_marker, "w") as f:
            f.write(d + "\n")
        return {"status": "failed", "diagnosis": d}
    return {"status": "done"}


def snapshot(folder, end_time):
    """The path of the last blocks VTU snapshot at or before END_TIME
    (blocks.pvd), or None."""
    pvd = os.path.join(folder, "dda", "blocks.pvd")
    if not os.path.exists(pvd):
        return None
    best = None
    for m in re.finditer(r'timestep="([^"]+)" file="([^"]+)"', open(pvd).read()):
        if float(m.group(1)) <= end_time + 1e-9:
            best = os.path.join(folder, "dda", m.group(2))
    return best


def loosened_zone(folder, width, end_time):
    """Height (m) above the roof of the highest block over the opening that
    moved down by more than each of LOOSE_THRESHOLDS beyond the far field
    (last VTU snapshot); None without a snapshot. The far field of a block
    is the median vertical displacement of the blocks at its level (centroid
    within 0.5 m in y) more than 2 B from the opening's centre line: the
    soft contacts (penalty 0.1 GN/m) let the whole column settle by several
    cm, which is not loosening."""
    vtu = snapshot(folder, end_time)
    if vtu is None:
        return None
    a = read_vtu.read(vtu)
    ids = a["block_id"].values
    disp = [d[1] for d in a["displacement"].tuples()]
    original = scene.read_blocks(os.path.join(folder, "cut", "blocks.dda"))
    x0, x1 = width / 2 - B / 2, width / 2 + B / 2
    geo = []
    for i in ids:
        poly = original[int(i)]
        ys = [p[1] for p in poly]
        geo.append((sum(p[0] for p in poly) / len(poly),
                    sum(ys) / len(ys), min(ys), max(ys)))
    far = sorted((g[1], d) for g, d in zip(geo, disp)
                 if abs(g[0] - width / 2) > 2 * B)
    far_y = [f[0] for f in far]

    def far_field(y):
        import bisect
        lo = bisect.bisect_left(far_y, y - 0.5)
        hi = bisect.bisect_right(far_y, y + 0.5)
        v = sorted(f[1] for f in far[lo:hi])
        return v[len(v) // 2] if v else 0.0

    heights = []
    for t in LOOSE_THRESHOLDS:
        h = 0.0
        for g, d in zip(geo, disp):
            if x0 < g[0] < x1 and g[2] >= ROOF_Y - 1e-6 and \
                    far_field(g[1]) - d > t:
                h = max(h, g[3] - ROOF_Y)
        heights.append(h)
    return heights


def collect(work, names, end_time):
    """Rows of models.csv and timeseries.csv."""
    rows, series = [], []
    table = {n: (length, b) for n, length, b in model_list()}
    for name in names:
        folder = os.path.join(work, name)
        width = 100.0 if name.endswith("-wide") else 60.0
        out = os.path.join(folder, "dda")
        s = summary(os.path.join(out, "summary.csv"))
        base, seed = split_seed(name)
        length, b = table.get(base, (None, None))
        row = {"model": name, "L_m": length or "", "b_m": b or "",
               "b_over_L": "%.1f" % (b / length) if length else ""}
        fail = os.path.join(folder, "FAILED")
        if os.path.exists(fail):
            row["status"] = "failed"
            row["diagnosis"] = open(fail).read().strip()
        elif s.get("completed") == "1" and \
                float(s.get("final_time", 0)) >= end_time - 1e-9:
            row["status"] = "done"
        else:
            row["status"] = "stopped"
        data, _ = measurement_rows(out)
        data = [r for r in data if float(r["time_s"]) <= end_time + 1e-9]
        row["final_time_s"] = data[-1]["time_s"] if data else ""
        blocks_file = os.path.join(folder, "cut", "blocks.dda")
        if os.path.exists(blocks_file):
            row["blocks"] = len(scene.read_blocks(blocks_file))
        for k in ("steps", "time_step_cuts",
                  "open_close_iterations_per_step"):
            row[k] = s.get(k, "")
        walls = os.path.join(folder, "wall.csv")
        if os.path.exists(walls):
            # Every invocation of the DDA (a resumed model has several).
            w = sum(float(line.split(",")[1]) for line in open(walls))
            row["wall_time"] = "%.1f" % w
            if s.get("steps"):
                row["ms_per_step"] = "%.2f" % (1e3 * w / float(s["steps"]))
        if data:
            last = data[-1]
            for p in range(1, 6):
                row["uy%d_m" % p] = last["mp%d_uy_m" % p]
                row["sx%d_Pa" % p] = last["mp%d_sigma_x_Pa" % p]
            next_t = 0.0
            for r in data:
                t = float(r["time_s"])
                if t + 1e-9 >= next_t:
                    for p in range(1, 6):
                        series.append({"model": name, "time_s": r["time_s"],
                                       "point": p,
                                       "uy_m": r["mp%d_uy_m" % p],
                                       "sigma_x_Pa": r["mp%d_sigma_x_Pa" % p]})
                    next_t += 0.05
        h = loosened_zone(folder, width, end_time)
        if h is not None:
            for t, v in zip(LOOSE_THRESHOLDS, h):
                row["loose_%gm_over_B" % t] = "%.3f" % (v / B)
        rows.append(row)
    return rows, series


def write_csv(path, rows, fields=None):
    if fields is None:
        fields = []
        for r in rows:
            for k in r:
                if k not in fields:
                    fields.append(k)
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    os.replace(path + ".tmp", path)


def fmt(v, scale=1.0, digits=3):
    try:
        return "%.*g" % (digits, float(v) * scale)
    except (TypeError, ValueError):
        return "-"


def markdown(rows, end_time):
    out = ["Layering study (thesis Table 3-1 models, Table 3-2 controls), "
           "end time %g s. uy: vertical displacement (mm, up positive) at "
           "points 1-5; sx: horizontal stress (kPa, compression negative); "
           "loosened zone: height over B of the highest block over the "
           "opening that moved down more than 0.05 / 0.1 / 0.2 m beyond the "
           "far field at its level." % end_time,
           "",
           "| model | L (m) | b/L | status | blocks | steps | cuts | wall (s) "
           "| ms/step | uy1 | uy2 | uy3 | uy4 | uy5 | sx1 | sx2 | sx3 | sx4 "
           "| sx5 | loose/B (0.05 / 0.1 / 0.2 m) |",
           "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:"
           "|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        cells = [r["model"], str(r.get("L_m", "")) or "-",
                 r.get("b_over_L") or "-", r["status"],
                 str(r.get("blocks", "-")), fmt(r.get("steps"), 1, 6),
                 fmt(r.get("time_step_cuts"), 1, 6),
                 fmt(r.get("wall_time"), 1, 4), r.get("ms_per_step", "-")]
        cells += [fmt(r.get("uy%d_m" % p), 1e3) for p in range(1, 6)]
        cells += [fmt(r.get("sx%d_Pa" % p), 1e-3) for p in range(1, 6)]
        cells.append(" / ".join(r.get("loose_%gm_over_B" % t, "-")
                                for t in LOOSE_THRESHOLDS))
        out.append("| " + " | ".join(cells) + " |")
    fails = [r for r in rows if r["status"] == "failed"]
    if fails:
        out += ["", "Failed models and the engine's diagnosis:", ""]
        out += ["- %s: %s" % (r["model"], r.get("diagnosis", "")) for r in fails]
    return "\n".join(out) + "\n"


def symlog_threshold(values_mm):
    """Linear range of the symlog axes (mm): the power of ten below the
    median |u| of the plotted values (100 mm at Table 3-2's penalty, 1 mm
    at 1e10 N/m, where the far field settles by 2-3 mm)."""
    v = sorted(abs(u) for u in values_mm if u)
    if not v:
        return 100.
    return 10. ** math.floor(math.log10(v[len(v) // 2]))


def plots(outdir, rows, series, work, end_time):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Fig. 3-7 C/D: FMML time series.
    fm = [s for s in series if s["model"] == "FMML"]
    if fm:
        fig, ax = plt.subplots(1, 3, figsize=(15, 4))
        for p in range(1, 6):
            t = [float(s["time_s"]) for s in fm if s["point"] == p]
            uy = [1e3 * float(s["uy_m"]) for s in fm if s["point"] == p]
            ax[0].plot(t, uy, label="point %d" % p)
            if p >= 3:
                ax[2].plot(t, uy, label="point %d" % p, color="C%d" % (p - 1))
            ax[1].plot(t, [-1e-3 * float(s["sigma_x_Pa"]) for s in fm
                           if s["point"] == p], label="point %d" % p)
        ax[2].set(xlabel="time (s)", ylabel="vertical displacement (mm)",
                  title="FMML, points 3-5 (zoom)")
        ax[2].legend()
        ax[0].set(xlabel="time (s)", ylabel="vertical displacement (mm)",
                  title="FMML (cf. thesis Fig. 3-7C)")
        ax[1].set(xlabel="time (s)",
                  ylabel="horizontal compressive stress (kPa)",
                  title="FMML (cf. thesis Fig. 3-7D)")
        ax[0].legend()
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "fig-3-7.png"), dpi=110)
        plt.close(fig)
    # Fig. 3-9: final displacement against b/L.
    plotted = [1e3 * float(r["uy%d_m" % p]) for r in rows for p in (3, 4, 5)
               if r.get("uy%d_m" % p) not in (None, "")]
    fig, ax = plt.subplots(1, 3, figsize=(13, 4), sharey=True)
    ref = {r["model"]: r for r in rows}
    for k, p in enumerate((3, 4, 5)):
        for length, style in ((5, "o-"), (10, "s-"), (15, "^-")):
            pts = [(float(r["b_over_L"]), 1e3 * float(r["uy%d_m" % p]))
                   for r in rows if str(r.get("L_m")) == str(length) and
                   r.get("uy%d_m" % p) not in (None, "")]
            if pts:
                pts.sort()
                ax[k].plot(*zip(*pts), style, label="DL, L = %d m" % length)
        f = ref.get("FMML")
        if f and f.get("uy%d_m" % p):
            ax[k].axhline(1e3 * float(f["uy%d_m" % p]), color="k", ls="--",
                          label="FMML")
        ax[k].set(xlabel="b / L", title="point %d" % p)
    ax[0].set_ylabel("final vertical displacement (mm, symlog)")
    for x in ax:
        x.set_yscale("symlog", linthresh=symlog_threshold(plotted))
    ax[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "fig-3-9.png"), dpi=110)
    plt.close(fig)
    # Fig. 3-7B / 3-8: deformed roof zone, coloured by vertical displacement.
    for name in ("FMML", "DL02", "DL07"):
        vtu = snapshot(os.path.join(work, name), end_time)
        if vtu is None:
            continue
        deformed_plot(vtu, "%s at t = %s s (vertical displacement, mm)"
                      % (name, fmt(ref.get(name, {}).get("final_time_s"), 1,
                                   4)),
                      os.path.join(outdir, "deformed-%s.png" % name))


def thin_moved_blocks(polys, displacement, width=0.15, moved=0.05):
    """Indices of the blocks thinner than WIDTH (m; area / diameter, the
    width of a sliver) that moved more than MOVED (m). At the scale of the
    deformed plots (~16 pixels per metre) such a sliver is one or two
    pixels wide and its black edges merge into a line: a chain of toppled
    slivers then looks like blocks crossing each other (DL07, issue 16)."""
    out = []
    for i, p in enumerate(polys):
        a = 0.5 * abs(sum(p[k][0] * p[(k + 1) % len(p)][1]
                          - p[(k + 1) % len(p)][0] * p[k][1]
                          for k in range(len(p))))
        d = max(math.dist(u, v) for u in p for v in p)
        if a / d < width and math.hypot(*displacement[i][:2]) > moved:
            out.append(i)
    return out


def deformed_plot(vtu, title, path, xlim=(15, 45), ylim=(4, 40)):
    """The blocks of the snapshot VTU coloured by their vertical
    displacement; when thin blocks moved (slivers), an inset enlarges them
    so that their real shapes (congruent, not crossing) can be seen."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    a = read_vtu.read(vtu)
    polys = read_vtu.polygons(a)
    disp = a["displacement"].tuples()
    uy = [1e3 * d[1] for d in disp]
    fig, ax = plt.subplots(figsize=(8, 5.5))

    def draw(axes, lw):
        pc = PolyCollection(polys, array=uy, cmap="viridis",
                            edgecolors="k", linewidths=lw)
        pc.set_clim(-200, 0)
        axes.add_collection(pc)
        return pc
    pc = draw(ax, 0.2)
    ax.set(xlim=xlim, ylim=ylim, aspect="equal", title=title)
    for p, y in enumerate(scene.POINTS_Y, 1):
        ax.plot(30.1, y, "r+")
        ax.annotate(str(p), (30.4, y), color="r")
    thin = [i for i in thin_moved_blocks(polys, disp)
            if xlim[0] < polys[i][0][0] < xlim[1]
            and ylim[0] < polys[i][0][1] < ylim[1]]
    if thin:
        xs = [v[0] for i in thin for v in polys[i]]
        ys = [v[1] for i in thin for v in polys[i]]
        half = 0.5 * max(max(xs) - min(xs), max(ys) - min(ys)) + 0.3
        cx, cy = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
        ins = ax.inset_axes([0.01, 0.01, 0.45, 0.45])
        draw(ins, 0.3)
        ins.set(xlim=(cx - half, cx + half), ylim=(cy - half, cy + half),
                aspect="equal", xticks=[], yticks=[])
        ins.text(0.03, 0.97, "%d thin blocks (< 15 cm)\nenlarged" % len(thin),
                 transform=ins.transAxes, va="top", fontsize=7,
                 bbox=dict(fc="w", ec="none", alpha=0.8))
        ax.indicate_inset_zoom(ins, edgecolor="r")
    fig.colorbar(pc, ax=ax)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

def seed_summary(rows):
    """Per base model (in order): the seeds and, for the final vertical
    displacement at points 3-5 (m) and the loosened zone (0.2 m, / B), the
    mean, the smallest and the largest over the models that are done."""
    out, order = {}, []
    for r in rows:
        base, seed = split_seed(r["model"])
        if base not in out:
            out[base] = {"model": base, "L_m": r.get("L_m", ""),
                         "b_over_L": r.get("b_over_L", ""), "seeds": [],
                         "values": {}}
            order.append(base)
        if r["status"] != "done":
            continue
        out[base]["seeds"].append(seed)
        for k in ("uy3_m", "uy4_m", "uy5_m", "loose_0.2m_over_B"):
            if r.get(k, "") != "":
                out[base]["values"].setdefault(k, []).append(float(r[k]))
    return [out[b] for b in order]


def seeds_markdown(summary_rows, end_time):
    out = ["Layering study over realizations (random seeds of the "
           "structure), end time %g s: mean [smallest, largest] over the "
           "seeds of the final vertical displacement (mm) at points 3-5 and "
           "of the loosened-zone height / B (0.2 m)." % end_time, "",
           "| model | L (m) | b/L | seeds | uy3 | uy4 | uy5 | loose/B |",
           "|---|---:|---:|---|---|---|---|---|"]
    for r in summary_rows:
        cells = [r["model"], str(r["L_m"]) or "-", r["b_over_L"] or "-",
                 ",".join(str(k) for k in sorted(r["seeds"])) or "-"]
        for k, scale in (("uy3_m", 1e3), ("uy4_m", 1e3), ("uy5_m", 1e3),
                         ("loose_0.2m_over_B", 1.0)):
            v = r["values"].get(k, [])
            if not v:
                cells.append("-")
                continue
            cells.append("%s [%s, %s]" % (fmt(sum(v) / len(v), scale),
                                          fmt(min(v), scale),
                                          fmt(max(v), scale)))
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out) + "\n"


def seeds_plot(path, summary_rows):
    """Fig. 3-9 over the seeds: the mean final vertical displacement at
    points 3, 4, 5 against b/L for each L, the range as error bars, FMML's
    mean and range as a band."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    threshold = symlog_threshold(
        [1e3 * u for r in summary_rows for p in (3, 4, 5)
         for u in r["values"].get("uy%d_m" % p) or []])
    for ax, p in zip(axes, (3, 4, 5)):
        k = "uy%d_m" % p
        for length, marker in ((5, "o"), (10, "s"), (15, "^")):
            pts = [(float(r["b_over_L"]), r["values"][k]) for r in
                   summary_rows if str(r["L_m"]) == str(length) and
                   r["values"].get(k)]
            if not pts:
                continue
            pts.sort(key=lambda q: q[0])
            x = [a for a, _ in pts]
            mean = [1e3 * sum(v) / len(v) for _, v in pts]
            lo = [m - 1e3 * min(v) for m, (_, v) in zip(mean, pts)]
            hi = [1e3 * max(v) - m for m, (_, v) in zip(mean, pts)]
            ax.errorbar(x, mean, yerr=[lo, hi], marker=marker, capsize=3,
                        label="DL, L = %d m" % length)
        fm = [r for r in summary_rows if r["model"] == "FMML"]
        if fm and fm[0]["values"].get(k):
            v = [1e3 * u for u in fm[0]["values"][k]]
            ax.axhspan(min(v), max(v), color="k", alpha=0.15)
            ax.axhline(sum(v) / len(v), color="k", ls="--",
                       label="FMML (mean, range)")
        ax.set_yscale("symlog", linthresh=threshold)
        ax.set_xlabel("b / L")
        ax.set_title("point %d" % p)
    axes[0].set_ylabel("final vertical displacement (mm, symlog)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)


def main():
    p = argparse.ArgumentParser(description="layering study (issue 16)")
    p.add_argument("rockdda")
    p.add_argument("--end-time", type=float, default=5.0)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--models", nargs="*")
    p.add_argument("--seeds", type=int, default=1,
                   help="also run random seeds 2..N of each model's "
                        "structure (folders NAME-sK)")
    p.add_argument("--runs", nargs="*",
                   help="run only these model folders (NAME or NAME-sK)")
    p.add_argument("--merge", metavar="SEEDS_CSV",
                   help="with --runs: the rows of an earlier seeds.csv that "
                        "these runs do not replace join the seeds tables "
                        "(a run that completed within the default limits "
                        "is the same run under looser ones)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a key of table-3-2.prm's DDA section")
    p.add_argument("--work")
    p.add_argument("--timeout", type=float)
    p.add_argument("--retry-failed", action="store_true")
    p.add_argument("--out", default=HERE)
    p.add_argument("--collect-only", action="store_true",
                   help="only write the tables and plots from WORK")
    a = p.parse_args()
    names = a.models or [n for n, _, _ in model_list()]
    seeded = names + ["%s-s%d" % (n, k) for k in range(2, a.seeds + 1)
                      for n in names]
    if a.runs:
        # Only the realizations asked for (and the models of --models).
        names = a.models or []
        seeded = names + [r for r in a.runs if r not in names]
    overrides = {}
    for kv in a.set:
        if "=" not in kv:
            raise SystemExit("study.py: --set takes KEY=VALUE, got '%s'" % kv)
        key, value = kv.split("=", 1)
        overrides[key.strip()] = value.strip()
    work = os.path.abspath(a.work or os.path.join(
        os.path.dirname(os.path.abspath(a.rockdda)), "layering-chapter-3"))
    os.makedirs(work, exist_ok=True)
    binary = os.path.join(work, "rockdda")
    if not os.path.exists(binary):
        shutil.copy2(a.rockdda, binary + ".tmp")
        os.replace(binary + ".tmp", binary)

    def stop(signum, frame):
        STOP.set()
    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGTERM, stop)

    status = {}
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        if a.collect_only:
            names_to_run = []
        else:
            names_to_run = seeded
        futures = {pool.submit(run_model, binary, work, n, a.end_time,
                               a.timeout, a.retry_failed, a.jobs,
                               overrides): n
                   for n in names_to_run}
        for f in concurrent.futures.as_completed(futures):
            n = futures[f]
            try:
                status[n] = f.result()
            except Exception as e:  # a broken model must not stop the rest
                status[n] = {"status": "failed", "diagnosis": repr(e)}
            print("%s: %s %s" % (n, status[n]["status"],
                                 status[n].get("diagnosis", "")), flush=True)
    rows, series = collect(work, names, a.end_time)
    os.makedirs(a.out, exist_ok=True)
    if names:
        write_seed_one_tables(a, work, rows, series)
    if a.seeds > 1 or a.runs:
        all_rows = rows + collect(work, seeded[len(names):], a.end_time)[0]
        if a.merge:
            new = {r["model"]: r for r in all_rows}
            earlier = read_csv(a.merge)
            known = {r["model"] for r in earlier}
            all_rows = [new.get(r["model"], r) for r in earlier] + \
                [r for r in all_rows if r["model"] not in known]
        write_csv(os.path.join(a.out, "seeds.csv"), all_rows)
        summary_rows = seed_summary(all_rows)
        sm = os.path.join(a.out, "seeds.md")
        with open(sm + ".tmp", "w") as f:
            f.write(seeds_markdown(summary_rows, a.end_time))
        os.replace(sm + ".tmp", sm)
        seeds_plot(os.path.join(a.out, "fig-3-9-seeds.png"), summary_rows)
        rows = all_rows
    return 0 if all(r["status"] == "done" for r in rows) else 1


def write_seed_one_tables(a, work, rows, series):
    """models.csv, timeseries.csv, results.md and the plots of seed 1."""
    write_csv(os.path.join(a.out, "models.csv"), rows)
    write_csv(os.path.join(a.out, "timeseries.csv"), series,
              ["model", "time_s", "point", "uy_m", "sigma_x_Pa"])
    md = os.path.join(a.out, "results.md")
    with open(md + ".tmp", "w") as f:
        f.write(markdown(rows, a.end_time))
    os.replace(md + ".tmp", md)
    plots(a.out, rows, series, work, a.end_time)


if __name__ == "__main__":
    sys.exit(main())
