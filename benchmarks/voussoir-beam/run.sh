#!/usr/bin/env bash
# Voussoir check of issue 16: bash benchmarks/voussoir-beam/run.sh BUILD_DIR
# Bisection of the critical friction angle of the jointed bed in DDA (default:
# Table 3-2's dynamic control 0.99 and dt = 0.5 ms, penalty 1e10 N/m) and
# its sensitivity to the time step, the penalty, the dynamic control and the
# joint spacing; writes critical.csv, runs-*.csv and result-*.md here and
# prints the Voussoir estimate (voussoir.py). About 2 minutes.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
# Builds under the shared build lock of this machine (two cores, several users).
[ -n "${ROCKDDA_SKIP_BUILD:-}" ] || flock /tmp/rockdda-build.lock cmake --build "$build" --target rockdda
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$build/rockdda" "$work/rockdda"
rm -f "$here/critical.csv" "$here"/runs-*.csv "$here"/result-*.md
study() { /usr/bin/python3 "$here/study.py" "$work/rockdda" --out "$here" \
  --tolerance 0.25 "$@" | tail -1; }
study --tag=-default
study --tag=-dt1e-3 --time-step 0.001
study --tag=-dt2.5e-4 --time-step 0.00025
study --tag=-dt1.25e-4 --time-step 0.000125
study --tag=-penalty1e9 --penalty 1e9
study --tag=-penalty1e11 --penalty 1e11
study --tag=-penalty1e8 --penalty 1e8
study --tag=-static --dynamic 0 --time-step 0.01 --end-time 30
study --tag=-static-dt5e-3 --dynamic 0 --time-step 0.005 --end-time 60
study --tag=-static-dt2.5e-3 --dynamic 0 --time-step 0.0025 --end-time 120
study --tag=-static-penalty1e11 --dynamic 0 --time-step 0.01 --end-time 30 --penalty 1e11
study --tag=-spacing0.5 --joint-spacing 0.5
study --tag=-spacing1 --joint-spacing 1
study --tag=-spacing1.75 --joint-spacing 1.75
/usr/bin/python3 "$here/voussoir.py"
