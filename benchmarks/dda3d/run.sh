#!/bin/bash
# 3D DDA benchmarks: the stability table at the extremes and the scaling of
# a running-bond wall of 100, 1,000 and 10,000 boxes, with the plot.
#   bash run.sh BUILD_DIR [MAX_BLOCKS] [STEPS_10K]
# BUILD_DIR holds unit-dda3d_stability and dda3d_scaling (cmake --build
# BUILD_DIR --target unit-dda3d_stability dda3d_scaling). MAX_BLOCKS
# (default 20000: all three walls; the 10,041-block wall takes ~2.5 s per
# step with the D-ILU CG, ~4 min for its medians) skips larger walls;
# STEPS_10K (default 3) timed steps of the 10,000-block wall. (The Fig. 4-2
# error tables: see README.md.)
set -euo pipefail
build=${1:?usage: run.sh BUILD_DIR [MAX_BLOCKS] [STEPS_10K]}
max=${2:-20000}
steps10k=${3:-3}
here=$(cd "$(dirname "$0")" && pwd)
/usr/bin/python3 "$here/stability_table.py" "$build" "$here"
"$build/dda3d_scaling" scaling "$max" "$steps10k" > "$here/scaling.csv"
/usr/bin/python3 "$here/plot_scaling.py" "$here"
cat "$here/scaling.csv" "$here/exponents.csv"
