#!/usr/bin/env bash
# Heat MPI benchmark: bash benchmarks/heat-mpi/run.sh [BUILD_DIR] [REFINEMENTS...]
# Runs heat_mpi_block.prm (Masada Block 1 size, 24 hourly Crank-Nicolson
# steps) at each number of global refinements (default: 5 6 7, i.e.
# 107,520 / 430,080 / 1,720,320 cells) in three configurations, three
# times each:
#   serial  one process, serial solver (CG + SSOR)
#   mpi-1   mpirun -np 1, distributed solver (Linear solver = amg)
#   mpi-2   mpirun -np 2, distributed solver (CG + AMG)
# and writes timings.csv (every run), results.md (medians, speed-up against
# serial in the same run, agreement of the probes) and timings.png.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
shift || true
levels=("${@:-5 6 7}")
levels=(${levels[*]})
cmake --build "$build" --target rockdda
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Containers often forbid the cross-memory attach of the shared-memory
# transport; plain copies work everywhere.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv="$here/timings.csv"
echo "refinements,config,repeat,cells,dofs,wall_time_s,solver_wall_time_s,max_rss_mb,final_probe1,final_probe2,final_block1_mean" > "$csv.tmp"
for level in "${levels[@]}"; do
  for config in serial mpi-1 mpi-2; do
    for repeat in 1 2 3; do
      dir="$work/$level-$config-$repeat"
      mkdir -p "$dir"
      prm="$dir/run.prm"
      sed -e "s/Global refinements    = 5/Global refinements    = $level/" \
          -e "s|Output directory = .*|Output directory = $dir/out|" \
          "$here/heat_mpi_block.prm" > "$prm"
      case $config in
        serial) cmd=("$build/rockdda" --quiet "$prm") ;;
        mpi-1)  sed -i 's/Linear solver       = cg/Linear solver       = amg/' "$prm"
                cmd=(mpirun --oversubscribe -np 1 "$build/rockdda" --quiet "$prm") ;;
        mpi-2)  cmd=(mpirun --oversubscribe -np 2 "$build/rockdda" --quiet "$prm") ;;
      esac
      # Peak resident memory: the largest of the processes (GNU time
      # reports the maximum over the process and its waited children).
      if [ -x /usr/bin/time ]; then
        /usr/bin/time -f "%M" -o "$dir/rss" "${cmd[@]}" > "$dir/stdout"
      else
        "${cmd[@]}" > "$dir/stdout"; echo 0 > "$dir/rss"
      fi
      s="$dir/out/summary.csv"
      get() { grep "^$1," "$s" | cut -d, -f2; }
      echo "$level,$config,$repeat,$(get cells),$(get dofs),$(get wall_time),$(get solver_wall_time),$(( $(cat "$dir/rss") / 1024 )),$(get final_probe1),$(get final_probe2),$(get final_block1_mean)" >> "$csv.tmp"
      echo "refinements $level $config run $repeat: $(get wall_time) s"
    done
  done
done
mv "$csv.tmp" "$csv"
/usr/bin/python3 "$here/plot.py" "$here"
