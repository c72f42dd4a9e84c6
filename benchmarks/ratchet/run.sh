#!/bin/bash
# Coupled DDA thermal-ratchet study of Masada Block 1 (issue 13):
# sensitivity, convergence and cost of the 'ratchet' analysis.
#   benchmarks/ratchet/run.sh BUILD_DIR [study.py options]
# BUILD_DIR holds rockdda (already built; this script does not build). Works
# from any working directory (ctest -L long runs it from this folder with
# the absolute build directory). Writes results.csv, cycles.csv, results.md
# and ratchet-study.png (and stability.csv / .md, stability.py) next to this
# script; about 7 minutes on 2 cores
# (one simulation at a time; --jobs 2 runs two). Exit status 1 if a run
# fails or the binary lacks the 'ratchet' analysis.
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR [study.py options]}" && pwd)
shift
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rockdda="$build/rockdda"
if [[ ! -x "$rockdda" ]]; then
  echo "run.sh: $rockdda not found (build it first: cmake --build $build)" >&2
  exit 1
fi
params=$("$rockdda" --print-parameters)
if ! grep -q 'Infill top depth' <<<"$params"; then
  echo "run.sh: $rockdda has no 'ratchet' analysis (rebuild it)" >&2
  exit 1
fi
# The no-infill control's long-run stability (10,000 cycles, ~2 min).
/usr/bin/python3 "$here/stability.py" "$rockdda" --out "$here"
exec /usr/bin/python3 "$here/study.py" "$rockdda" --out "$here" "$@"
