#!/usr/bin/env bash
# Analytical ratchet benchmark: bash benchmarks/ratchet/analytical/run.sh BUILD_DIR
# Runs the 'ratchet-analytical' analysis of Masada Block 1
# (parameter-files/masada/ratchet-analytical.prm) as it stands and with the
# unit weight scaled so that F_max fits the thesis, then writes
# reproduction.csv, reproduction.md and figure_5_13.png next to this script
# (a few seconds).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
cmake --build "$build" --target rockdda
/usr/bin/python3 "$here/reproduce.py" "$build/rockdda" \
  "$here/../../../parameter-files/masada/ratchet-analytical.prm" "$here"
