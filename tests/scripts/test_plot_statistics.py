#!/usr/bin/python3
"""ctest scripts.plot_statistics: scripts/plot_statistics.py on a small
statistics.csv (issue 11, item 9).

Checks the unit parsing (kinetic_energy_J_m -> J/m, not "J [m]"), one panel
per unit with several lines, a clear error without traceback (exit 1) on an
unknown column, and the shebang. Exits 77 (ctest: skipped) if matplotlib is
missing for this interpreter.
usage: test_plot_statistics.py SCRIPT SCRATCH_DIR
"""
import importlib.util
import os
import shutil
import subprocess
import sys

try:
    import matplotlib  # noqa: F401
except ImportError:
    print("matplotlib is not installed for", sys.executable, "- skipped")
    sys.exit(77)

script, scratch = sys.argv[1], sys.argv[2]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


spec = importlib.util.spec_from_file_location("plot_statistics", script)
plot = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot)

# Unit parsing, as rockdda encodes units ('/' -> '_', '^' -> 'p').
for name, expected in [
        ("kinetic_energy_J_m", ("kinetic energy", "J/m")),
        ("velocity_m_s", ("velocity", "m/s")),
        ("time_s", ("time", "s")),
        ("mp1_ux_m", ("mp1 ux", "m")),
        ("mp1_sigma_x_Pa", ("mp1 sigma x", "Pa")),
        ("area_mp2", ("area", "m^2")),
        ("acceleration_m_sp2", ("acceleration", "m/s^2")),
        ("gradient_K_m", ("gradient", "K/m")),
        ("probe1_degC", ("probe1", "degC")),
        ("contacts_open", ("contacts open", "")),
        ("friction", ("friction", ""))]:
    got = plot.split_unit(name)
    check(got == expected, f"split_unit({name}) = {got}, expected {expected}")
check(plot.label("kinetic_energy_J_m") == "kinetic energy [J/m]",
      "label(kinetic_energy_J_m) = " + plot.label("kinetic_energy_J_m"))

# A small DDA-like statistics.csv: 11 columns against time, 5 units.
folder = os.path.join(scratch, "plot-statistics")
shutil.rmtree(folder, ignore_errors=True)
os.makedirs(folder)
header = ["time_s", "dt_s", "cuts", "contacts_open", "kinetic_energy_J_m",
          "strain_energy_J_m", "contact_energy_J_m", "mp1_ux_m", "mp1_uy_m",
          "mp1_sigma_x_Pa", "mp1_sigma_y_Pa"]
with open(os.path.join(folder, "statistics.csv"), "w") as f:
    f.write(",".join(header) + "\n")
    for i in range(20):
        t = 0.01 * i
        f.write(",".join(str(v) for v in [t, 0.01, i % 2, 3, t * t, t, 2 * t,
                                          -t, t / 2, 1e5, 2e5]) + "\n")
groups = plot.group_by_unit(header[1:])
check(list(groups) == ["s", "", "J/m", "m", "Pa"],
      f"one group per unit: {list(groups)}")
check(groups["J/m"] == header[4:7], "three energies share the J/m panel")

run = subprocess.run([script, folder], capture_output=True, text=True)
check(run.returncode == 0, f"plot runs (exit {run.returncode}) {run.stderr}")
check(os.path.isfile(os.path.join(folder, "statistics.png")),
      "statistics.png written")
check("5 panels" in run.stdout, "5 panels: " + run.stdout.strip())

run = subprocess.run([script, folder, "kinetic_energy_J_m", "no_such_m"],
                     capture_output=True, text=True)
check(run.returncode == 1, f"unknown column: exit {run.returncode}")
check("Traceback" not in run.stderr, "unknown column: no traceback")
check("no_such_m" in run.stderr and "kinetic_energy_J_m" in run.stderr,
      "unknown column: message names it and lists the columns: "
      + run.stderr.strip())

run = subprocess.run([script, os.path.join(folder, "missing")],
                     capture_output=True, text=True)
check(run.returncode == 1 and "Traceback" not in run.stderr,
      "missing folder: clear error " + run.stderr.strip())

with open(script) as f:
    shebang = f.readline().strip()
check(shebang == "#!/usr/bin/python3", "shebang " + shebang)
check(os.access(script, os.X_OK), "the script is executable")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
