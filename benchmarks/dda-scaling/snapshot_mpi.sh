#!/bin/bash
# Output at scale (issue 16, item 5): collective HDF5 + XDMF snapshots of a
# synthetic running-bond wall from 1 and 2 MPI ranks, alternating, ROUNDS
# rounds (each run writes a series of 3 snapshots and reports the median
# write; rank 0 reads the last one back and checks every value).
#   bash snapshot_mpi.sh BUILD_DIR [COLUMNS COURSES ROUNDS FOLDER] > snapshot-mpi.csv
# BUILD_DIR holds snapshot_mpi (cmake --build BUILD_DIR --target
# snapshot_mpi). Defaults: 1000 x 1000 bricks (10^6 blocks), 3 rounds,
# files in /tmp/rockdda-snapshot-mpi (about 1.2 GiB, removed at the end).
set -euo pipefail
build=${1:?usage: snapshot_mpi.sh BUILD_DIR [COLUMNS COURSES ROUNDS FOLDER]}
columns=${2:-1000}
courses=${3:-1000}
rounds=${4:-3}
folder=${5:-/tmp/rockdda-snapshot-mpi}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
header=1
for round in $(seq "$rounds"); do
  for np in 1 2; do
    rm -rf "$folder"
    sync # no write-back of the previous run's files during this one
    out=$(mpirun --allow-run-as-root --oversubscribe -np "$np" \
      "$build/snapshot_mpi" "$columns" "$courses" 3 "$folder")
    if [ "$header" = 1 ]; then
      echo "round,$(echo "$out" | head -1)"
      header=0
    fi
    echo "$round,$(echo "$out" | tail -1)"
  done
done
rm -rf "$folder"
