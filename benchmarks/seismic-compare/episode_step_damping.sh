#!/bin/bash
# The episode-step table of README.md ("What on the scene needs the short
# step") with the contact dashpots of the episodes (issue 15, the bedding
# joint's damping): trace_scene_event SEED YEAR DT damping=ZETA for the four
# traced events at 5, 2.5, 1.25 and 0.625 ms (or the steps in $STEPS, e.g.
# the +-4 % bands: STEPS="0.0048 0.0052 0.0024 0.0026 0.0012 0.0013 0.0006
# 0.00065"), one run at a time.
#   [STEPS="..."] benchmarks/seismic-compare/episode_step_damping.sh BUILD_DIR [ZETA ...]
# Writes episode-step-damping.csv next to this script (zeta, seed, year, dt,
# slip and dynamic slip in mm, max rotation, dynamic steps, cuts, balance
# change and energy in play in J/m, wall time in s). Default zetas: 0 0.05.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="$(cd "${1:?usage: $0 BUILD_DIR [ZETA ...]}" && pwd)"
shift
[ $# -gt 0 ] && zetas=("$@") || zetas=(0 0.05)
csv="$here/episode-step-damping.csv"
[ -f "$csv" ] || echo "zeta,seed,year,dt,slip_mm,dynamic_slip_mm,max_rotation,dynamic_steps,cuts,balance_change,energy_scale,wall_s" > "$csv"
for zeta in "${zetas[@]}"; do
  for event in "3 90" "1 198" "4 116" "2 149"; do
    set -- $event
    for dt in ${STEPS:-0.005 0.0025 0.00125 0.000625}; do
      line=$("$build/trace_scene_event" "$1" "$2" "$dt" "damping=$zeta" | tail -1)
      echo "$line" >&2
      python3 - "$zeta" "$1" "$2" "$dt" "$line" >> "$csv" <<'PY'
import re, sys
zeta, seed, year, dt, line = sys.argv[1:]
num = r"([-+0-9.eE]+)"
m = re.search(r"slip " + num + r" mm \(dynamic " + num + r" mm\), max rotation "
              + num + r" rad, (\d+) dynamic steps, (\d+) cuts, balance change "
              + num + " of " + num + r" J/m, " + num + " s", line)
print(",".join([zeta, seed, year, dt] + list(m.groups())))
PY
    done
  done
done
