#!/usr/bin/env bash
# Heat half-space benchmark: bash benchmarks/heat-halfspace/run.sh BUILD_DIR
# Builds the benchmark, runs the half-space sweep and the 1,000-cycle block
# timing (a few minutes), and writes sweep.csv, block.csv, block_timing.csv,
# block_study.csv, results.md and the PNG plots next to this script.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
cmake --build "$build" --target heat_halfspace
"$build/heat_halfspace" "$here"
# Block-accuracy study (3 cycles each) against a fine reference.
study=$(mktemp -d)
echo "config,degree,coarse_cell_m,band_width_m,band_cell_m,dt_h,dofs,steps,wall_time_s,max_mean_error_K,max_gradient_error_K_m" > "$here/block_study.csv"
for cfg in "2 1 1 0.125 1" "1 1.75 0.5 0.25 3" "1 1.75 0.5 0.5 3" "1 1 0 0 3" "2 1.75 0 0 3" "2 1.75 0 0 6" "2 2.5 0.5 0.5 3"; do
  dir="$study/${cfg// /_}"; mkdir -p "$dir"
  "$build/heat_halfspace" "$dir" 3 $cfg > /dev/null
  echo "$cfg" >> "$study/configs"
done
/usr/bin/python3 "$here/plot.py" "$here" "$study"
rm -rf "$study"
