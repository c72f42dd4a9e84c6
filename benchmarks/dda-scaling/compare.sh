#!/bin/bash
# Before/after timing of two builds on the same machine, back to back:
#   bash compare.sh BASE_BUILD_DIR NEW_BUILD_DIR [RUNS]
# Each case runs RUNS times (default 7), alternating base and new; prints
# the median ms/step of each and the ratio new/base (default solver: block
# D-ILU CG on two threads). Build both with --target dda_scaling.
set -euo pipefail
base=${1:?usage: compare.sh BASE_BUILD NEW_BUILD [RUNS]}
new=${2:?usage: compare.sh BASE_BUILD NEW_BUILD [RUNS]}
runs=${3:-7}
cases=("10 10 0 400" "10 10 1 400" "25 40 0 80" "25 40 1 80" "80 125 0 10" "80 125 1 10")
echo "rows,columns,dynamic,steps,base_ms_per_step,new_ms_per_step,ratio"
for c in "${cases[@]}"; do
  read -r rows cols dyn steps <<< "$c"
  b=(); n=()
  for ((r = 0; r < runs; ++r)); do
    b+=("$("$base/dda_scaling" single "$rows" "$cols" "$dyn" dilu2 "$steps" | sed 's/.*: \([0-9.]*\) ms\/step.*/\1/')")
    n+=("$("$new/dda_scaling" single "$rows" "$cols" "$dyn" dilu2 "$steps" | sed 's/.*: \([0-9.]*\) ms\/step.*/\1/')")
  done
  /usr/bin/python3 - "$rows" "$cols" "$dyn" "$steps" "${b[*]}" "${n[*]}" <<'PY'
import statistics, sys
rows, cols, dyn, steps, b, n = sys.argv[1:]
mb = statistics.median(map(float, b.split()))
mn = statistics.median(map(float, n.split()))
print(f"{rows},{cols},{dyn},{steps},{mb:.3f},{mn:.3f},{mn / mb:.3f}")
PY
done
