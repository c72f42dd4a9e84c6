#!/usr/bin/env bash
# Sliding-block benchmark: bash benchmarks/sliding-block/run.sh BUILD_DIR
# Builds the benchmark, runs it (a few minutes), writes results.csv,
# suite.csv, results.md and error_vs_cost.png next to this script.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
cmake --build "$build" --target sliding_block_benchmark
"$build/sliding_block_benchmark" "$here"
/usr/bin/python3 "$here/plot.py" "$here"
