#!/usr/bin/python3
"""ctest interrupt.*: interrupted runs keep their data, and a new run into
the same folder leaves no files of the earlier one (issue 11, item 3).

usage: test_interrupt.py DRIVER SOURCE_DIR SCRATCH_DIR CASE
CASE:
  dda_sigint   a long dda run (the stack of tests/regression/dda_stack.prm
               for 1e4 s) gets SIGINT once it writes VTU snapshots: exit 130,
               a message naming the signal and the folder, statistics.csv,
               log.txt, summary.csv with 'completed,0,-', checkpoint.bin;
               Resume = true then continues it to a later End time (exit 0,
               'completed,1,-').
  dda_sigterm  the same with SIGTERM: exit 143.
  dda_settling a dda run in its settling steps (before t = 0) gets SIGINT:
               exit 130, log.txt naming the steps done, summary.csv with
               'completed,0,-'; there is no time series yet.
  heat_sigint  a heat run in its spin-up gets SIGINT: exit 130,
               statistics.csv, log.txt, summary.csv (completed = 0),
               checkpoint.bin.
  calibrate_sigterm, earthquakes_sigint, compare_sigint
               a calibrate grid / an earthquakes / a compare run long enough
               to be interrupted: exit 143 / 130 / 130, summary.csv
               'completed,0,-', the runs done kept in calibration.csv /
               events.csv (at least one finite, the rest NaN) /
               catalogues.csv (at least one complete catalogue, not all),
               log.txt, parameters.prm.
  stale        a dda run with many VTU snapshots, then a shorter one into the
               same folder: the VTU files on disk are exactly those of the
               new blocks.pvd and contacts.pvd, no checkpoint.bin is left, and
               a file rockdda did not write is kept.
"""
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import time

driver, source, scratch, case = sys.argv[1:5]
driver, source, scratch = (os.path.abspath(p) for p in (driver, source, scratch))
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def dda_prm(folder, end_time, output_interval, resume=False,
            checkpoint_interval=0, settling_steps=0):
    blocks = os.path.join(source, "tests", "regression", "dda_stack.blocks")
    return f"""set Analysis type    = dda
set Output directory = {folder}
subsection DDA
  set Block file      = {blocks}
  set End time        = {end_time}
  set Time step       = 0.01
  set Dynamic control = 0
  set Contact penalty = 1e11
  set Output interval = {output_interval}
  set Resume          = {"true" if resume else "false"}
  set Checkpoint interval = {checkpoint_interval}
  set Settling steps  = {settling_steps}
end
"""


def heat_prm(folder):
    return f"""set Analysis type    = heat
set Output directory = {folder}
subsection Heat
  subsection Geometry
    set Blocks        = 0, -30; 0.25, -30; 0.25, 0; 0, 0
    set Boundary tags = far field, adiabatic, exposed, adiabatic
  end
  subsection Mesh
    set Finite element degree = 2
    set Coarse cell size      = 0.25
  end
  subsection Time stepping
    set Time step      = 3600
    set End time       = 31557600
    set Spin-up cycles = 1000
    set Spin-up period = 31557600
  end
  subsection Boundary condition 1
    set Tag       = exposed
    set Type      = temperature
    set Data      = sinusoids
    set Mean      = 20
    set Sinusoids = 9, 31557600, 0
  end
  subsection Boundary condition 2
    set Tag  = far field
    set Type = flux
  end
end
"""


def write(name, text):
    path = os.path.join(scratch, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def summary(folder):
    rows = {}
    with open(os.path.join(folder, "summary.csv")) as f:
        for line in f.read().splitlines()[1:]:
            parts = line.split(",")
            rows[parts[0]] = parts[1]
    return rows


def interrupt(prm, folder, ready, sig, expected_rc, min_rows=1,
              files=("statistics.csv", "log.txt", "summary.csv",
                     "checkpoint.bin", "parameters.prm")):
    """Start the driver on prm, wait until ready() is true, send sig;
    check the exit status and the files an interrupted run keeps."""
    proc = subprocess.Popen([driver, "--quiet", prm], cwd=scratch,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    start = time.time()
    while not ready() and proc.poll() is None and time.time() - start < 120:
        time.sleep(0.02)
    check(proc.poll() is None, "the run is still going when signalled")
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        check(False, "the run stops within 120 s of the signal")
    print("stderr:", err.strip())
    check(proc.returncode == expected_rc,
          f"exit status {proc.returncode} is {expected_rc}")
    name = signal.Signals(sig).name
    check(f"interrupted by {name}" in err, f"stderr says 'interrupted by {name}'")
    check(os.path.abspath(folder) in err, "stderr names the output folder")
    for f in files:
        check(os.path.isfile(os.path.join(folder, f)), f + " written")
    if os.path.isfile(os.path.join(folder, "summary.csv")):
        check(summary(folder).get("completed") == "0",
              "summary.csv: completed = 0")
    if os.path.isfile(os.path.join(folder, "log.txt")):
        with open(os.path.join(folder, "log.txt")) as f:
            log = f.read()
        check(f"interrupted by {name}" in log, "log.txt says interrupted")
    if "statistics.csv" in files:
        with open(os.path.join(folder, "statistics.csv")) as f:
            rows = f.read().splitlines()
        check(len(rows) >= 1 + min_rows,
              f"statistics.csv has a header and >= {min_rows} rows "
              f"({len(rows) - 1})")


def pvd_files(path):
    with open(path) as f:
        return set(re.findall(r'file="([^"]+)"', f.read()))


os.makedirs(scratch, exist_ok=True)
folder = os.path.join(scratch, "out-" + case)
shutil.rmtree(folder, ignore_errors=True)

if case in ("dda_sigint", "dda_sigterm"):
    sig = signal.SIGINT if case == "dda_sigint" else signal.SIGTERM
    prm = write(case + ".prm", dda_prm(folder, 1e4, 0.01))
    interrupt(prm, folder,
              lambda: os.path.exists(os.path.join(folder, "blocks-00002.vtu")),
              sig, 128 + int(sig))
    if case == "dda_sigint" and not failures:
        reached = float(summary(folder)["final_time"])
        prm = write(case + "-resume.prm",
                    dda_prm(folder, reached + 0.1, 0.01, resume=True))
        r = subprocess.run([driver, "--quiet", prm], cwd=scratch,
                           capture_output=True, text=True, timeout=120)
        check(r.returncode == 0, f"resumed run exits 0 ({r.returncode}: "
              f"{r.stderr.strip()})")
        s = summary(folder)
        check(s.get("completed") == "1", "resumed run: completed = 1")
        check(abs(float(s.get("final_time", "nan")) - (reached + 0.1)) < 1e-9,
              "resumed run reaches the new End time")
elif case == "dda_settling":
    prm = write(case + ".prm", dda_prm(folder, 1, 0.1, settling_steps=100000))
    # 100,000 static steps of the stack (the key's largest value) take
    # about 1.2 s on this project's 2-core machine: signal 0.3 s after the
    # analysis starts, well inside them (a 1 s wait missed the settling
    # under the load of ctest -j2).
    def settling():
        if not os.path.exists(os.path.join(folder, "parameters.prm")):
            return False
        time.sleep(0.3)
        return True
    interrupt(prm, folder, settling, signal.SIGINT, 130,
              files=("log.txt", "summary.csv", "parameters.prm"))
    with open(os.path.join(folder, "log.txt")) as f:
        check("stopped while settling, after" in f.read(),
              "log.txt says how many settling steps were done")
elif case == "heat_sigint":
    prm = write(case + ".prm", heat_prm(folder))
    # parameters.prm is written just before the analysis starts.
    def started():
        if not os.path.exists(os.path.join(folder, "parameters.prm")):
            return False
        time.sleep(1.0)
        return True
    # Stopped in the spin-up: no rows are recorded yet.
    interrupt(prm, folder, started, signal.SIGINT, 130, min_rows=0)
elif case == "compare_sigint":
    prm = write(case + ".prm", f"""set Analysis type    = compare
set Output directory = {folder}
subsection Compare
  set Number of catalogues = 40
  set Threads              = 2
  set Plot                 = false
end
""")
    def dda_started():
        log = os.path.join(folder, "parameters.prm")
        if not os.path.exists(log):
            return False
        time.sleep(5.0)
        return True
    interrupt(prm, folder, dda_started, signal.SIGINT, 130,
              files=("log.txt", "summary.csv", "parameters.prm",
                     "catalogues.csv", "events.csv"))
    path = os.path.join(folder, "catalogues.csv")
    if os.path.isfile(path):
        with open(path) as f:
            rows = f.read().splitlines()[1:]
        check(1 <= len(rows) < 40,
              f"catalogues.csv: {len(rows)} complete catalogues kept")
elif case in ("calibrate_sigterm", "earthquakes_sigint"):
    if case == "calibrate_sigterm":
        sig, table = signal.SIGTERM, "calibration.csv"
        prm = write(case + ".prm", f"""set Analysis type    = calibrate
set Output directory = {folder}
subsection Calibration
  set Penalties   = 1e9, 5e9, 1e10, 5e10, 1e11, 5e11, 1e12, 2e12
  set Time steps  = 0.001
  set Frequencies = 1.3, 3.8
  set Duration    = 60
  set Threads     = 2
  set Plot        = false
end
""")
    else:
        sig, table = signal.SIGINT, "events.csv"
        prm = write(case + ".prm", f"""set Analysis type    = earthquakes
set Output directory = {folder}
subsection Earthquakes
  set Magnitudes             = 7.5
  set Number of realisations = 200
  set Recurrence intervals   = 4000
  set Threads                = 2
  set Plot                   = false
end
""")
    def started():
        if not os.path.exists(os.path.join(folder, "parameters.prm")):
            return False
        time.sleep(3.0)
        return True
    interrupt(prm, folder, started, sig, 128 + int(sig),
              files=("log.txt", "summary.csv", "parameters.prm", table))
    path = os.path.join(folder, table)
    if os.path.isfile(path):
        with open(path) as f:
            rows = [line.split(",") for line in f.read().splitlines()[1:]]
        column = 4 if case == "calibrate_sigterm" else 4  # the 'dda' column
        finite = [r for r in rows if r[column] not in ("nan", "-nan", "")]
        check(len(finite) >= 1, f"{table}: {len(finite)} runs done kept")
        check(len(finite) < (16 if case == "calibrate_sigterm" else 200),
              f"{table}: not every run was done ({len(finite)})")
elif case == "stale":
    # A file the user put there is never removed.
    os.makedirs(folder)
    mine = os.path.join(folder, "notes-blocks-00099.vtu")
    with open(mine, "w") as f:
        f.write("user's file\n")
    for end, interval, checkpoints in [(2, 0.01, 0.5), (0.5, 0.1, 0)]:
        prm = write(case + ".prm",
                    dda_prm(folder, end, interval,
                            checkpoint_interval=checkpoints))
        r = subprocess.run([driver, "--quiet", prm], cwd=scratch,
                           capture_output=True, text=True, timeout=120)
        check(r.returncode == 0, f"run to {end} s exits 0 ({r.stderr.strip()})")
    for series in ["blocks", "contacts"]:
        listed = pvd_files(os.path.join(folder, series + ".pvd"))
        on_disk = {os.path.basename(p)
                   for p in glob.glob(os.path.join(folder, series + "-*.vtu"))}
        check(on_disk == listed,
              f"{series}: {len(on_disk)} VTU files on disk, "
              f"{len(listed)} in {series}.pvd")
    check(not os.path.exists(os.path.join(folder, "checkpoint.bin")),
          "no checkpoint.bin of the earlier run")
    check(os.path.exists(mine), "a file rockdda did not write is kept")
    with open(os.path.join(folder, "log.txt")) as f:
        check("files of an earlier run" in f.read(),
              "log.txt says the earlier run's files were removed")
else:
    sys.exit("unknown case " + case)

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
