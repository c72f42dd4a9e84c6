#!/usr/bin/env bash
# Layering study of thesis Chapter 3.4-3.5 (issue 16):
#   bash benchmarks/layering-chapter-3/run.sh BUILD_DIR [END_TIME] [extra study.py options]
# Runs the 16 models of Table 3-1 (parameter-files/layering) with the DDA
# controls of Table 3-2, two at a time, each resumable from its checkpoint
# (run the command again after a kill: finished models are skipped, the
# others resume), and writes models.csv, timeseries.csv, results.md and
# the PNG plots here. Work folder: BUILD_DIR/layering-chapter-3. END_TIME
# defaults to 5 s (thesis); measured ~6 min per model at 5 s on the 2-core
# machine, i.e. ~50 min for the matrix (see README.md).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
end=${2:-5}
shift $(( $# > 2 ? 2 : $# ))
# Builds under the shared build lock of this machine (two cores, several users).
[ -n "${ROCKDDA_SKIP_BUILD:-}" ] || flock /tmp/rockdda-build.lock cmake --build "$build" --target rockdda
exec /usr/bin/python3 "$here/study.py" "$build/rockdda" --end-time "$end" \
  --work "$build/layering-chapter-3" "$@"
