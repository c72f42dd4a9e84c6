#!/bin/bash
# Before/after timing of two builds on the same machine, back to back:
#   bash compare.sh BASE_BUILD_DIR NEW_BUILD_DIR [RUNS] [SOLVER]
# Each case runs RUNS times (default 7), alternating base and new; prints
# the median ms/step of each and the ratio new/base, and the same for the
# wall-clock time per simulated millisecond (a build whose steps are cut
# more often covers less simulated time in the same number of steps).
# SOLVER is one of dda_scaling's (default dilu2: block D-ILU CG on two
# threads; dilu: on one thread, which a concurrent build on a 2-core
# machine disturbs less). Build both with --target dda_scaling.
set -euo pipefail
base=${1:?usage: compare.sh BASE_BUILD NEW_BUILD [RUNS] [SOLVER]}
new=${2:?usage: compare.sh BASE_BUILD NEW_BUILD [RUNS] [SOLVER]}
runs=${3:-7}
solver=${4:-dilu2}
# Cases "ROWS COLUMNS DYNAMIC STEPS", separated by commas in COMPARE_CASES
# (default: section 1's walls and step counts).
IFS=, read -r -a cases <<< "${COMPARE_CASES:-10 10 0 400,10 10 1 400,25 40 0 80,25 40 1 80,80 125 0 10,80 125 1 10}"
echo "rows,columns,dynamic,steps,solver,base_ms_per_step,new_ms_per_step,ratio,base_it_per_step,new_it_per_step,base_cuts,new_cuts,base_ms_per_simulated_ms,new_ms_per_simulated_ms,ratio_per_simulated_time"
for c in "${cases[@]}"; do
  read -r rows cols dyn steps <<< "$c"
  b=(); n=()
  for ((r = 0; r < runs; ++r)); do
    b+=("$("$base/dda_scaling" single "$rows" "$cols" "$dyn" "$solver" "$steps")")
    n+=("$("$new/dda_scaling" single "$rows" "$cols" "$dyn" "$solver" "$steps")")
  done
  printf '%s\n' "${b[@]}" > /tmp/compare-base.$$
  printf '%s\n' "${n[@]}" > /tmp/compare-new.$$
  /usr/bin/python3 - "$rows" "$cols" "$dyn" "$steps" "$solver" /tmp/compare-base.$$ /tmp/compare-new.$$ <<'PY'
import re, statistics, sys
rows, cols, dyn, steps, solver, fb, fn = sys.argv[1:]
def parse(f):
    out = []
    for line in open(f):
        ms = float(re.search(r"([0-9.]+) ms/step", line).group(1))
        it = float(re.search(r"([0-9.]+) open-close", line).group(1))
        cuts = int(re.search(r"(\d+) cuts", line).group(1))
        end = float(re.search(r"simulated time ([0-9.e+-]+) s", line).group(1))
        begin = float(re.search(r"timed from ([0-9.e+-]+) s", line).group(1))
        out.append((ms, it, cuts, ms * int(steps) / (1e3 * (end - begin))))
    return out
b, n = parse(fb), parse(fn)
med = lambda v, i: statistics.median(x[i] for x in v)
print(f"{rows},{cols},{dyn},{steps},{solver},{med(b,0):.3f},{med(n,0):.3f},"
      f"{med(n,0)/med(b,0):.3f},{med(b,1):.2f},{med(n,1):.2f},{b[0][2]},{n[0][2]},"
      f"{med(b,3):.3f},{med(n,3):.3f},{med(n,3)/med(b,3):.3f}")
PY
  rm -f /tmp/compare-base.$$ /tmp/compare-new.$$
done
