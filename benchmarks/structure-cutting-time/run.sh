#!/usr/bin/env bash
# Cutting-time benchmark: bash benchmarks/structure-cutting-time/run.sh BUILD_DIR [MAX_SEGMENTS]
# Builds and runs structure_cutting_time (about a minute for 100k segments
# on one core), then writes results.csv, results.md and cutting_time.png here.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
[ -n "${ROCKDDA_SKIP_BUILD:-}" ] || cmake --build "$build" --target structure_cutting_time
"$build/structure_cutting_time" "$here" "${2:-100000}"
/usr/bin/python3 "$here/plot.py" "$here"
