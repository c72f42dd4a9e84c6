#!/usr/bin/env bash
# Boundary check of the layering study with an identical central structure
# (issue 16, item 1):
#   bash benchmarks/layering-chapter-3/boundary_check.sh BUILD_DIR [MODEL] [X0 X1]
# Cuts MODEL (default FMML; any parameter-files/layering/MODEL.prm) on a
# 100 m wide domain (opening at x = 45-55 m; the model's own file with the
# domain widened), clips the same blocks to the window X0 <= x <= X1
# (default 20-80 m: the study's 60 m domain centred on the same opening;
# window.py fixes the blocks on the new sides), adds points 1-5 at
# x = 50.1 m to both, and runs both with the DDA controls of Table 3-2
# (5 s, one thread each, both at once). Prints points 1-5 at the end of both
# runs. Work folder: BUILD_DIR/layering-boundary-check/MODEL-X0-X1 (rerun to
# resume; finished runs are kept).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
layering=$here/../../parameter-files/layering
build=$(cd "${1:-$here/../../build}" && pwd)
model=${2:-FMML}
x0=${3:-20}
x1=${4:-80}
work=$build/layering-boundary-check/$model-$x0-$x1
mkdir -p "$work"
cd "$work"
sed -e "s#^set Output directory.*#set Output directory = cut-wide#" \
    -e "s#^\(\s*set Domain\s*=\).*#\1 0, 0; 100, 0; 100, 40; 0, 40#" \
    -e "s#^\(\s*set Excavations\s*=\).*#\1 45, 10; 55, 10; 55, 16; 45, 16#" \
    "$layering/$model.prm" > cut-wide.prm
[ -f cut-wide/blocks.dda ] || "$build/rockdda" --quiet cut-wide.prm
/usr/bin/python3 "$layering/window.py" cut-wide/blocks.dda "$x0" "$x1" > window.dda
for m in wide window; do
  src=$([ $m = wide ] && echo cut-wide/blocks.dda || echo window.dda)
  /usr/bin/python3 "$layering/scene.py" "$src" --width 100 > scene-$m.dda
  resume=false
  [ -f dda-$m/checkpoint.bin ] && resume=true
  sed -e "s#^set Output directory.*#set Output directory = dda-$m#" \
      -e "s#^\(\s*set Block file\s*=\).*#\1 scene-$m.dda#" \
      -e "s#^\(\s*set Resume\s*=\).*#\1 $resume\n  set Threads = 1#" \
      "$layering/table-3-2.prm" > dda-$m.prm
done
pids=()
for m in wide window; do
  if ! grep -q "^completed,1" dda-$m/summary.csv 2>/dev/null; then
    "$build/rockdda" --quiet dda-$m.prm > run-$m.log 2>&1 &
    pids+=($!)
  fi
done
for p in "${pids[@]}"; do wait "$p"; done
for m in wide window; do
  echo "== $model $m: $(grep -c '^block' "$([ $m = wide ] && echo cut-wide/blocks.dda || echo window.dda)") blocks"
  grep -E "^(final_time|steps|time_step_cuts|mp[1-5]_uy)," dda-$m/summary.csv
done
