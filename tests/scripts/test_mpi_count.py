#!/usr/bin/env python3
"""The MPI counting library of benchmarks/dda-scaling (mpi_count.cc) counts
what a program sends: run the ping-pong (mpi_pingpong) on 2 ranks under it.
The message plan is known exactly: 7 sizes (8 B to 2 MiB, x 8), 5 rounds of
REPEAT round trips each. Asserted: each rank's MPI_Send count and bytes equal
the plan, what rank 0 sends rank 1 receives and the other way round (bytes are
conserved), and one barrier per round.

    test_mpi_count.py MPIEXEC LIBRARY PINGPONG WORKDIR
"""
import csv
import os
import subprocess
import sys

mpiexec, library, pingpong, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
prefix = os.path.join(work, "count")
for r in (0, 1):
    if os.path.exists(f"{prefix}.{r}.csv"):
        os.remove(f"{prefix}.{r}.csv")
repeat = 20
subprocess.run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-np", "2",
                "-x", "LD_PRELOAD=" + library, "-x",
                "ROCKDDA_MPI_COUNT=" + prefix, pingpong, str(repeat)],
               check=True, stdout=subprocess.DEVNULL)


def counts(rank):
    with open(f"{prefix}.{rank}.csv") as f:
        return {r["function"]: r for r in csv.DictReader(f)}


c = [counts(0), counts(1)]
sizes = [8 * 8**k for k in range(7)]
calls = 5 * repeat * len(sizes)
total = 5 * repeat * sum(sizes)
failures = []


def expect(what, got, want):
    if got != want:
        failures.append(f"{what}: {got}, expected {want}")


for r in (0, 1):
    expect(f"rank {r} MPI_Send calls", int(c[r]["MPI_Send"]["calls"]), calls)
    expect(f"rank {r} MPI_Send bytes", int(c[r]["MPI_Send"]["bytes_sent"]),
           total)
    expect(f"rank {r} MPI_Recv calls", int(c[r]["MPI_Recv"]["calls"]), calls)
    expect(f"rank {r} MPI_Barrier calls", int(c[r]["MPI_Barrier"]["calls"]),
           5 * len(sizes))
expect("bytes rank 0 sent = bytes rank 1 received",
       int(c[0]["MPI_Send"]["bytes_sent"]),
       int(c[1]["MPI_Recv"]["bytes_received"]))
expect("bytes rank 1 sent = bytes rank 0 received",
       int(c[1]["MPI_Send"]["bytes_sent"]),
       int(c[0]["MPI_Recv"]["bytes_received"]))
if failures:
    sys.exit("test_mpi_count: " + "; ".join(failures))
print(f"test_mpi_count: {calls} messages, {total} bytes each way, counted "
      "exactly on both ranks")
