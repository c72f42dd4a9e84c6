#!/usr/bin/env bash
# The shaking-table wedge (thesis Sec. 4.6-4.7.2) in 3D DDA against the
# analytical rigid wedge: error and wall time against the contact penalty
# (the thesis's 10-40 GN/m up to 1e3 x) and the time step, both seismic
# modes; the plot of the slide history. Usage: run.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
py=/usr/bin/python3
"$build/make_wedge_scene" "$root/parameter-files/dda3d-shaking-table.blocks"
hist=$(mktemp -d)
trap 'rm -rf "$hist"' EXIT
cd "$here"
$py shaking_table.py "$build/rockdda" \
  "$root/parameter-files/dda3d-shaking-table.blocks" \
  --penalty 1e10,2e10,4e10,1e11,1e12,1e13,2e13,4e13 --dt 0.005 \
  --out shaking_table.csv --histories "$hist"
$py shaking_table.py "$build/rockdda" \
  "$root/parameter-files/dda3d-shaking-table.blocks" \
  --penalty 1e10,4e10,1e12 --dt 0.002,0.001 --out shaking_table_dt.csv
# The same with the stiff-mode velocity solve (key 'Stiff mode velocity').
$py shaking_table.py "$build/rockdda" \
  "$root/parameter-files/dda3d-shaking-table.blocks" \
  --penalty 1e10,2e10,4e10,1e11,1e12,1e13,2e13,4e13 --dt 0.005 \
  --stiff-velocity true --out shaking_table_stiff_velocity.csv \
  --histories "$hist"
$py shaking_table.py "$build/rockdda" \
  "$root/parameter-files/dda3d-shaking-table.blocks" \
  --penalty 1e10,4e10,1e12 --dt 0.002,0.001 --stiff-velocity true \
  --out shaking_table_dt_stiff_velocity.csv
$py plot_history.py "$hist" shaking_table.png loading-0.005-4e10 \
  displacement-0.005-4e10 loading-0.005-2e10 loading-0.005-1e12-sv \
  displacement-0.005-1e12-sv loading-0.005-4e13-sv
# The documented setting (penalty 4e10 N/m, dt 0.005 s) must finish within
# 5 % of the analytical history in both modes; the other rows are the study
# (README: runs at >= 1e12 N/m stop with a diagnosis).
$py - <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open("shaking_table.csv"))
        if r["penalty_N_per_m"] == "4e10" and r["dt_s"] == "0.005"]
bad = [r for r in rows if r["status"] != "ok" or float(r["error_history"]) >= 0.05]
print("documented setting:", [(r["mode"], r["error_history"]) for r in rows])
sys.exit(1 if bad or len(rows) != 2 else 0)
PY
