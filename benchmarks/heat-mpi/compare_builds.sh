#!/usr/bin/env bash
# Two builds timed back to back on benchmarks/heat-mpi/heat_mpi_block.prm
# (serial, mpirun -np 1 with amg, mpirun -np 2), old and new alternating in
# each repeat so that both see the same load; wall times from summary.csv.
# usage: OLD=DIR NEW=DIR compare_builds.sh OUT.csv REPEATS LEVELS...
set -uo pipefail
# OLD and NEW: the two build folders (each with rockdda and heat_halfspace).
old=${OLD:?set OLD to the old build folder}; new=${NEW:?set NEW to the new build folder}
out=$1; reps=$2; shift 2
prm0=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/heat-mpi/heat_mpi_block.prm
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
echo "level,config,repeat,binary,wall_time_s,solver_wall_time_s,elapsed_s,final_probe1" > $out
work=$(mktemp -d)
for level in "$@"; do
 for rep in $(seq 1 $reps); do
  for config in serial mpi-1 mpi-2; do
   order="old new"; [ $((rep % 2)) -eq 0 ] && order="new old"
   for bin in $order; do
    exe=${!bin}/rockdda
    dir=$work/$level-$config-$rep-$bin; mkdir -p $dir
    prm=$dir/run.prm
    sed -e "s/Global refinements    = 5/Global refinements    = $level/" \
        -e "s|Output directory = .*|Output directory = $dir/out|" $prm0 > $prm
    case $config in
      serial) cmd=($exe --quiet $prm) ;;
      mpi-1) sed -i 's/Linear solver       = cg/Linear solver       = amg/' $prm
             cmd=(mpirun --oversubscribe -np 1 $exe --quiet $prm) ;;
      mpi-2) cmd=(mpirun --oversubscribe -np 2 $exe --quiet $prm) ;;
    esac
    t0=$(date +%s.%N)
    "${cmd[@]}" > $dir/stdout 2>&1
    t1=$(date +%s.%N)
    s=$dir/out/summary.csv
    get() { grep "^$1," $s | cut -d, -f2; }
    echo "$level,$config,$rep,$bin,$(get wall_time),$(get solver_wall_time),$(echo "$t1 - $t0" | bc),$(get final_probe1)" >> $out
   done
  done
 done
done
rm -rf $work
