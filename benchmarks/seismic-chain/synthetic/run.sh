#!/bin/bash
# Synthetic motion and site amplification (issue 14, items 4-5).
#   benchmarks/seismic-chain/synthetic/run.sh BUILD_DIR
# BUILD_DIR holds unit-seismic_synthetic (already built; this script does
# not build). Its test SyntheticBenchmark.Study, with ROCKDDA_SYNTHETIC_OUT
# set, writes the data (50 seeds per M 6-7.5 and Rjb 10-50 km for Q0 = 600
# and 180, El Centro before and after the Masada site amplification, error
# against cost of the seeds and the time step); plot.py then writes
# synthetic-pga-vs-bjf97.png, el-centro-masada-site.png and results.md next
# to this script. About 10 s. Exit status 1 if a median of the default
# parameters is not within a factor 1.5 of BJF97 or a run fails.
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
test="$build/unit-seismic_synthetic"
if [[ ! -x "$test" ]]; then
  echo "run.sh: $test not found (build it first: cmake --build $build)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
ROCKDDA_SYNTHETIC_OUT="$work" "$test" --gtest_filter='SyntheticBenchmark.Study' \
  | grep -v '^\[' | grep -v '^Running main\|^Note:' | tee "$work/log.txt"
exec /usr/bin/python3 "$here/plot.py" "$work" --out "$here"
