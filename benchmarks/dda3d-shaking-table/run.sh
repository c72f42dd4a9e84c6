#!/usr/bin/env bash
# The shaking-table wedge (thesis Sec. 4.6-4.7.2) in 3D DDA against the
# analytical rigid wedge: error and wall time against the normal contact
# penalty (the thesis's 10-40 GN/m up to 1e3 x), the shear penalty and the
# time step, both seismic modes; the plot of the slide history.
# Usage: run.sh BUILD_DIR [--older]   (~6 min; --older also re-measures
# the tables of the sections before "Shear penalty", ~6 min more)
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR [--older]}" && pwd)
older=${2:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
py=/usr/bin/python3
blocks="$root/parameter-files/dda3d-shaking-table.blocks"
"$build/make_wedge_scene" "$blocks"
hist=$(mktemp -d)
trap 'rm -rf "$hist"' EXIT
cd "$here"
penalties=1e10,2e10,4e10,1e11,1e12,1e13,2e13,4e13
documented="--stiff-velocity true"
# The documented setting (parameter-files/dda3d-shaking-table.prm): shear
# penalty 1e9 N/m whatever the normal one.
$py shaking_table.py "$build/rockdda" "$blocks" --penalty $penalties \
  $documented --shear-penalty 1e9 --out shaking_table_documented.csv \
  --histories "$hist"
# The same with the shear penalty tied to the normal one (0.4 p).
$py shaking_table.py "$build/rockdda" "$blocks" --penalty $penalties \
  $documented --out shaking_table_tied_shear.csv --histories "$hist"
# The shear penalty swept at two normal penalties.
$py shaking_table.py "$build/rockdda" "$blocks" --penalty 1e12,4e13 \
  $documented --shear-penalty 1e9,4e9,2e10,1e11,4e11 \
  --out shaking_table_shear_sweep.csv
# The time step at the documented setting.
$py shaking_table.py "$build/rockdda" "$blocks" --penalty 4e10,1e12,4e13 \
  $documented --shear-penalty 1e9 --dt 0.002,0.001 \
  --out shaking_table_dt_documented.csv
$py plot_history.py "$hist" shaking_table.png \
  loading-0.005-4e10-sv-ks1e9 displacement-0.005-4e10-sv-ks1e9 \
  loading-0.005-4e13-sv-ks1e9 loading-0.005-4e13-sv
if [ "$older" = "--older" ]; then
  # Shi's velocity, each contact its own strength, shear 0.4 p (the
  # engine's defaults), then the stiff-mode velocity alone.
  $py shaking_table.py "$build/rockdda" "$blocks" --penalty $penalties \
    --out shaking_table.csv
  $py shaking_table.py "$build/rockdda" "$blocks" \
    --penalty 1e10,4e10,1e12 --dt 0.002,0.001 --out shaking_table_dt.csv
  $py shaking_table.py "$build/rockdda" "$blocks" --penalty $penalties \
    --stiff-velocity true --out shaking_table_stiff_velocity.csv
  $py shaking_table.py "$build/rockdda" "$blocks" \
    --penalty 1e10,4e10,1e12 --dt 0.002,0.001 --stiff-velocity true \
    --out shaking_table_dt_stiff_velocity.csv
fi
# The documented setting must finish within 5 % of the analytical history
# in both modes at every normal penalty from 1e10 to 4e13 N/m (the issue's
# bound; 1.7 % at most when measured).
$py - <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open("shaking_table_documented.csv"))
        if r["mode"] != "analytical"]
bad = [r for r in rows if r["status"] != "ok" or float(r["error_history"]) >= 0.05]
print("documented setting:", [(r["mode"], r["penalty_N_per_m"], r["error_history"]) for r in rows])
sys.exit(1 if bad or len(rows) != 16 else 0)
PY
