#!/usr/bin/env bash
# usage: OLD=DIR NEW=DIR compare_builds_cpu.sh OUT.csv REPEATS CYCLES
# CPU (user + system) and wall time, old/new alternating, N repeats:
# heat_halfspace's Block 1 run of C cycles, and the heat-mpi file at
# refinement 5 in the three configurations.
set -uo pipefail
# OLD and NEW: the two build folders (each with rockdda and heat_halfspace).
old=${OLD:?set OLD to the old build folder}; new=${NEW:?set NEW to the new build folder}
out=$1; reps=$2; cycles=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
echo "case,repeat,binary,cpu_s,wall_s" > $out
work=$(mktemp -d)
prm0=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/heat-mpi/heat_mpi_block.prm
for rep in $(seq 1 $reps); do
  order="old new"; [ $((rep % 2)) -eq 0 ] && order="new old"
  for bin in $order; do
    d=$work/h-$bin-$rep; mkdir -p $d
    /usr/bin/time -f "%U %S %e" -o $d/t ${!bin}/heat_halfspace $d $cycles > /dev/null 2>&1
    read u s e < $d/t; echo "block-$cycles-cycles,$rep,$bin,$(echo "$u + $s" | bc),$e" >> $out
    for config in serial mpi-1 mpi-2; do
      d=$work/m-$config-$bin-$rep; mkdir -p $d
      sed -e "s|Output directory = .*|Output directory = $d/out|" $prm0 > $d/run.prm
      case $config in
        serial) cmd=(${!bin}/rockdda --quiet $d/run.prm) ;;
        mpi-1) sed -i 's/Linear solver       = cg/Linear solver       = amg/' $d/run.prm
               cmd=(mpirun --oversubscribe -np 1 ${!bin}/rockdda --quiet $d/run.prm) ;;
        mpi-2) cmd=(mpirun --oversubscribe -np 2 ${!bin}/rockdda --quiet $d/run.prm) ;;
      esac
      /usr/bin/time -f "%U %S %e" -o $d/t "${cmd[@]}" > /dev/null 2>&1
      read u s e < $d/t; echo "heat-mpi-5-$config,$rep,$bin,$(echo "$u + $s" | bc),$e" >> $out
    done
  done
done
rm -rf $work
