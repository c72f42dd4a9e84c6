#!/bin/bash
# rockdda against USGS SLAMMER on its 90 rigid and 2,520 flexible
# (decoupled, coupled) sliding-block results (issue 14, item 7).
#   benchmarks/seismic-chain/flexible/run.sh BUILD_DIR
# BUILD_DIR holds unit-flexible_sliding (already built; this script does not
# build). The unit test runs the whole suite and, with ROCKDDA_FLEXIBLE_CSV
# set, writes every value; plot.py then writes flexible-vs-slammer.png and
# results.md next to this script. A few seconds. Exit status 1 if the test
# fails (a criterion of the issue is not met).
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
test="$build/unit-flexible_sliding"
if [[ ! -x "$test" ]]; then
  echo "run.sh: $test not found (build it first: cmake --build $build)" >&2
  exit 1
fi
csv="$here/values.csv"
ROCKDDA_FLEXIBLE_CSV="$csv" "$test" --gtest_filter='FlexibleSliding.SlammerSuite' \
  | grep -v '^\[' | sed -n '/^records scaled/,$p'
exec /usr/bin/python3 "$here/plot.py" "$csv" --out "$here"
