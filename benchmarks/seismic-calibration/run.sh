#!/bin/bash
# Calibration of DDA's numerical control (issue 15, item 1; thesis 5.5.2,
# Fig. 5-16).
#   benchmarks/seismic-calibration/run.sh BUILD_DIR
# BUILD_DIR holds rockdda (already built; this script does not build) and,
# if built, unit-calibrate. Works from any working directory. Runs
# parameter-files/masada/calibrate-block1.prm (36 DDA runs of Masada Block 1
# against the analytical sliding block), writes results.md (the error grid,
# the best pairs, wall times) and calibration.png next to this script; then
# parameter-files/masada/calibrate-block1-el-centro.prm (the same grid
# under El Centro x 2.56 in loading and displacement mode, 36 runs: wall
# time of each run against its error), appends its table to results.md and
# writes el-centro-calibration.csv and el-centro-calibration.png; then runs
# unit-calibrate (El Centro at both calibrated pairs and modes). Exit status
# 1 if a run fails or a check fails: every run finishes, each grid takes
# under 300 s, the thesis' pair (500 GN/m, 0.005 s) is within 15 % at both
# frequencies, the best error per frequency is below 5 %, and on El Centro
# the thesis' and rockdda's pair (100 GN/m, 0.005 s) are within 10 % in
# both modes.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../run_prm.sh"
run_prm "${1:-}" masada/calibrate-block1.prm calibration.png
python3 - "$out" "$here/results.md" <<'PY' || status=1
import csv, math, os, sys
out, md = sys.argv[1], sys.argv[2]
rows = list(csv.reader(open(os.path.join(out, "calibration.csv"))))
head, data = rows[0], [[float(x) for x in r] for r in rows[1:]]
c = {h.split("_")[0] if not h.startswith(("time_step", "max_rot", "wall"))
     else h.rsplit("_", 1)[0]: i for i, h in enumerate(head)}
summ = {r[0]: r[1] for r in csv.reader(open(os.path.join(out, "summary.csv")))}
freqs = sorted({r[c["frequency"]] for r in data})
ks = sorted({r[c["penalty"]] for r in data})
dts = sorted({r[c["time_step"]] for r in data}, reverse=True)
err = {(r[c["frequency"]], r[c["penalty"]], r[c["time_step"]]): r for r in data}
lines = ["# Calibration grid (measured by run.sh)", "",
         "Eq. 5.10 error R_e (%) of the final slip, Block 1 without infill, "
         "0.5 g sinusoid for 5 s, loading mode; columns: time step.", ""]
ok = True
for f in freqs:
    lines += [f"## {f:g} Hz (analytical slip "
              f"{float(summ[f'analytical_f{f:g}Hz']) * 1e3:.2f} mm)", "",
              "| k (GN/m) | " + " | ".join(f"dt = {dt:g} s" for dt in dts)
              + " |", "|---|" + "---|" * len(dts)]
    for k in ks:
        lines.append(f"| {k / 1e9:g} | " + " | ".join(
            f"{err[(f, k, dt)][c['error']]:.3g}" for dt in dts) + " |")
    best = min((r for r in data if r[c["frequency"]] == f),
               key=lambda r: r[c["error"]])
    lines += ["", f"best: k = {best[c['penalty']] / 1e9:g} GN/m, dt = "
              f"{best[c['time_step']]:g} s, R_e = {best[c['error']]:.3g} %", ""]
    if not best[c["error"]] < 5.:
        ok = False
        print(f"check failed: best error at {f:g} Hz is {best[c['error']]:.3g} %")
    cal = err[(f, 5e11, 0.005)][c["error"]]
    if not cal < 15.:
        ok = False
        print(f"check failed: 500 GN/m, 0.005 s at {f:g} Hz: {cal:.3g} %")
lines += [f"Product of the errors: best k = "
          f"{float(summ['best_penalty_product']) / 1e9:g} GN/m, dt = "
          f"{float(summ['best_time_step_product']):g} s.", "",
          "## Speed against accuracy", "",
          "| dt (s) | steps (1.3 Hz) | wall time per run (ms), mean | "
          "median R_e for k >= 100 GN/m (%) |", "|---|---|---|---|"]
for dt in dts:
    rs = [r for r in data if r[c["time_step"]] == dt]
    ws = sum(r[c["wall_time"]] for r in rs) / len(rs)
    es = sorted(r[c["error"]] for r in rs if r[c["penalty"]] >= 1e11)
    st = [r[c["steps"]] for r in rs if r[c["frequency"]] == freqs[0]]
    lines.append(f"| {dt:g} | {min(st):.0f}-{max(st):.0f} | {1e3 * ws:.1f} | "
                 f"{es[len(es) // 2]:.3g} |")
gw = float(summ["grid_wall_time"])
lines += ["", f"Whole grid: {len(data)} runs in {gw:.3f} s wall time "
          f"({summ['concurrent_runs']} at once; "
          f"{float(summ['run_wall_time_sum']):.3f} s summed over the runs), "
          f"failed runs: {summ['failed_runs']}."]
if float(summ["failed_runs"]) != 0 or not gw < 300.:
    ok = False
    print("check failed: failed runs or grid wall time >= 300 s")
open(md, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
sys.exit(0 if ok else 1)
PY

# El Centro over the same grid, both modes.
run_prm "$build" masada/calibrate-block1-el-centro.prm calibration.png \
  el-centro-calibration.png
cp "$out/calibration.csv" "$here/el-centro-calibration.csv"
python3 - "$out" "$here/results.md" <<'PY' || status=1
import csv, os, statistics, sys
out, md = sys.argv[1], sys.argv[2]
rows = list(csv.reader(open(os.path.join(out, "calibration.csv"))))
head, data = rows[0], [[float(x) for x in r] for r in rows[1:]]
c = {n: next(i for i, h in enumerate(head) if h == n or h.startswith(n + "_"))
     for n in ("penalty", "time_step", "error", "wall_time", "steps", "mode")}
summ = {r[0]: r[1] for r in csv.reader(open(os.path.join(out, "summary.csv")))}
ks = sorted({r[c["penalty"]] for r in data})
dts = sorted({r[c["time_step"]] for r in data}, reverse=True)
run = {(r[c["mode"]], r[c["penalty"]], r[c["time_step"]]): r for r in data}
modes = {0.: "loading", 1.: "displacement"}
exact = float(summ["analytical_record"])
lines = ["", "# El Centro over the calibration grid (measured by run.sh)", "",
         f"ELC-180 scaled to PGA 0.8 g, 39.5 s; analytical slip "
         f"{exact * 1e3:.2f} mm. Eq. 5.10 error R_e (%) and wall time of "
         "each run (ms, settling included; "
         f"{summ['concurrent_runs']} runs at once).", "",
         "| k (GN/m) | dt (s) | R_e loading (%) | wall loading (ms) | "
         "R_e displacement (%) | wall displacement (ms) | steps (loading) |",
         "|---|---|---|---|---|---|---|"]
for k in ks:
    for dt in dts:
        lo, di = run[(0., k, dt)], run[(1., k, dt)]
        lines.append(f"| {k / 1e9:g} | {dt:g} | {lo[c['error']]:.3g} | "
                     f"{1e3 * lo[c['wall_time']]:.0f} | {di[c['error']]:.3g} | "
                     f"{1e3 * di[c['wall_time']]:.0f} | {lo[c['steps']]:.0f} |")
lines += ["", "| dt (s) | wall time per run (ms), mean | median R_e for "
          "k >= 100 GN/m, both modes (%) |", "|---|---|---|"]
for dt in dts:
    rs = [r for r in data if r[c["time_step"]] == dt]
    es = [r[c["error"]] for r in rs if r[c["penalty"]] >= 1e11]
    lines.append(f"| {dt:g} | "
                 f"{1e3 * statistics.mean(r[c['wall_time']] for r in rs):.0f}"
                 f" | {statistics.median(es):.3g} |")
for m, name in modes.items():
    lines.append("")
    lines.append(f"best in {name} mode: k = "
                 f"{float(summ[f'best_penalty_record_{name}']) / 1e9:g} GN/m, "
                 f"dt = {float(summ[f'best_time_step_record_{name}']):g} s, "
                 f"R_e = {float(summ[f'best_error_record_{name}']):.3g} %")
gw = float(summ["grid_wall_time"])
lines += ["", f"Whole grid: {len(data)} runs in {gw:.2f} s wall time "
          f"({float(summ['run_wall_time_sum']):.2f} s summed over the runs), "
          f"failed runs: {summ['failed_runs']}."]
ok = True
for k in (5e11, 1e11):
    for m, name in modes.items():
        e = run[(m, k, 0.005)][c["error"]]
        if not e < 10.:
            ok = False
            print(f"check failed: El Centro, {k / 1e9:g} GN/m, 0.005 s, "
                  f"{name} mode: {e:.3g} %")
if float(summ["failed_runs"]) != 0 or not gw < 300.:
    ok = False
    print("check failed: failed El Centro runs or grid wall time >= 300 s")
open(md, "a").write("\n".join(lines) + "\n")
print("\n".join(lines))
sys.exit(0 if ok else 1)
PY
run_unit calibrate "El Centro|Hz:"
exit $status
