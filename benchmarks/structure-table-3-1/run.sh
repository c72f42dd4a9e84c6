#!/usr/bin/env bash
# Thesis Table 3-1 structure study: bash benchmarks/structure-table-3-1/run.sh BUILD_DIR [SEEDS]
# Runs the layered model (FMML) and the 15 DL models (L = 5, 10, 15 m;
# b = L/5 ... L; s = 0.54 m; DR = 0.5) on the same 60 m x 40 m domain and bed
# sequence, for each seed (default "1 2 3"), then writes results.csv,
# results.md and table_3_1.png here. About a minute.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
seeds=${2:-"1 2 3"}
[ -n "${ROCKDDA_SKIP_BUILD:-}" ] || cmake --build "$build" --target rockdda
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "model,seed,L_m,b_m,blocks,mean_width_m,median_width_m,mean_area_m2,p21_joints_per_m,p10_horizontal_per_m" > "$here/results.csv"
run() { # name seed confined dl L b plots
  local prm="$work/$1-$2.prm" out="$work/out-$1-$2"
  sed -e "s|@OUT@|$out|" -e "s|@SEED@|$2|" -e "s|@CONFINED@|$3|" \
      -e "s|@DL@|$4|" -e "s|@L@|$5|" -e "s|@B@|$6|" -e "s|@PLOTS@|$7|" \
      "$here/model.prm.in" > "$prm"
  "$build/rockdda" "$prm" > /dev/null
  get() { grep "^$1," "$out/summary.csv" | cut -d, -f2; }
  echo "$1,$2,$5,$6,$(get blocks),$(get mean_block_width),$(get median_block_width),$(get mean_block_area),$(get p21_joints),$(get p10_horizontal)" >> "$here/results.csv"
  if [ "$7" = true ]; then
    cp "$out/blocks.png" "$here/blocks-$1.png"
    cp "$out/histograms.png" "$here/histograms-$1.png"
  fi
}
for seed in $seeds; do
  plots=false; [ "$seed" = "$(echo $seeds | cut -d' ' -f1)" ] && plots=true
  run FMML "$seed" true false 5 1 "$plots"
  model=1
  for L in 5 10 15; do
    for i in 1 2 3 4 5; do
      b=$((L / 5 * i))
      p=false; [ "$plots" = true ] && { [ $model = 1 ] || [ $model = 10 ]; } && p=true
      run "$model" "$seed" false true "$L" "$b" "$p"
      model=$((model + 1))
    done
  done
done
/usr/bin/python3 "$here/plot.py" "$here"
