#!/bin/bash
# Runs the DDA scaling and accuracy-vs-cost benchmark and makes the plot.
#   bash run.sh BUILD_DIR [MAX_BLOCKS]
# BUILD_DIR holds the dda_scaling executable (cmake --build BUILD_DIR
# --target dda_scaling). MAX_BLOCKS (default 20000) skips larger walls.
set -euo pipefail
build=${1:?usage: run.sh BUILD_DIR [MAX_BLOCKS]}
max=${2:-20000}
here=$(cd "$(dirname "$0")" && pwd)
"$build/dda_scaling" scaling "$max" > "$here/scaling.csv"
"$build/dda_scaling" accuracy > "$here/accuracy.csv"
"$build/dda_scaling" tolerance > "$here/tolerance.csv"
/usr/bin/python3 "$here/plot.py" "$here"
cat "$here/scaling.csv" "$here/tolerance.csv"
