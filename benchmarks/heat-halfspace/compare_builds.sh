#!/usr/bin/env bash
# Two builds timed back to back on the heat_halfspace program (full run:
# sweep, adaptive study, 1,000 cycles of Block 1), old and new alternating.
# usage: OLD=DIR NEW=DIR compare_builds.sh OUT.csv REPEATS
set -uo pipefail
# OLD and NEW: the two build folders (each with rockdda and heat_halfspace).
old=${OLD:?set OLD to the old build folder}; new=${NEW:?set NEW to the new build folder}
out=$1; reps=$2
echo "repeat,binary,elapsed_s,block_wall_s" > $out
for rep in $(seq 1 $reps); do
  order="old new"; [ $((rep % 2)) -eq 0 ] && order="new old"
  for bin in $order; do
    dir=$(mktemp -d)
    t0=$(date +%s.%N)
    ${!bin}/heat_halfspace $dir > $dir/stdout 2>&1
    t1=$(date +%s.%N)
    bw=$(tail -1 $dir/block_timing.csv | cut -d, -f5)
    echo "$rep,$bin,$(echo "$t1 - $t0" | bc),$bw" >> $out
    rm -rf $dir
  done
done
