/**
 * @file
 * Point-to-point latency and bandwidth between ranks 0 and 1 (a ping-pong),
 * for the communication model of benchmarks/dda-scaling/mpi_volume.py:
 * prints "bytes,one_way_seconds" for messages of 8 B to 4 MiB, each the
 * median of 5 rounds of a timed loop of round trips (2000 round trips per
 * round up to 64 KiB, 50 above, or REPEAT for every size).
 *
 *   mpirun -np 2 build/mpi_pingpong [REPEAT]
 */
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mpi.h>
#include <vector>

int
main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2)
    {
      if (rank == 0)
        std::fprintf(stderr, "mpi_pingpong: run it on 2 ranks\n");
      MPI_Finalize();
      return 1;
    }
  const int repeat = argc > 1 ? std::atoi(argv[1]) : 0;
  if (rank == 0)
    std::printf("bytes,one_way_seconds\n");
  for (std::size_t bytes = 8; bytes <= (std::size_t(4) << 20); bytes *= 8)
    {
      std::vector<char>   buffer(bytes);
      const int           n = repeat > 0 ? repeat : bytes <= 65536 ? 2000 : 50;
      std::vector<double> rounds;
      for (int round = 0; round < 5; ++round)
        {
          MPI_Barrier(MPI_COMM_WORLD);
          const double start = MPI_Wtime();
          for (int k = 0; k < n && rank < 2; ++k)
            if (rank == 0)
              {
                MPI_Send(buffer.data(),
                         static_cast<int>(bytes),
                         MPI_CHAR,
                         1,
                         0,
                         MPI_COMM_WORLD);
                MPI_Recv(buffer.data(),
                         static_cast<int>(bytes),
                         MPI_CHAR,
                         1,
                         0,
                         MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
              }
            else
              {
                MPI_Recv(buffer.data(),
                         static_cast<int>(bytes),
                         MPI_CHAR,
                         0,
                         0,
                         MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
                MPI_Send(buffer.data(),
                         static_cast<int>(bytes),
                         MPI_CHAR,
                         0,
                         0,
                         MPI_COMM_WORLD);
              }
          rounds.push_back((MPI_Wtime() - start) / (2. * n));
        }
      std::sort(rounds.begin(), rounds.end());
      if (rank == 0)
        std::printf("%zu,%.6e\n", bytes, rounds[2]);
    }
  MPI_Finalize();
  return 0;
}
