#!/usr/bin/env bash
# Heat convergence benchmark: bash benchmarks/heat-convergence/run.sh BUILD_DIR
# Builds and runs the manufactured-solution sweeps (a few seconds) and writes
# space.csv, time.csv, results.md and the PNG plots next to this script.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
cmake --build "$build" --target heat_convergence
"$build/heat_convergence" "$here"
/usr/bin/python3 "$here/plot.py" "$here"
