/**
 * @file
 * Output at scale (issue 16, item 5): a synthetic running-bond wall of
 * COLUMNS x COURSES bricks (tests/unit/synthetic_snapshot.h; no DDA run)
 * written as a series of REPEAT collective HDF5 snapshots with XDMF indices
 * from every MPI rank (each rank owns a contiguous half, third, ... of the
 * bricks and the contacts of its bricks), then read back by rank 0 with the
 * serial reader and compared value by value with the generator.
 *
 *   mpirun -np 2 build/snapshot_mpi COLUMNS COURSES REPEAT FOLDER
 *
 * Prints one CSV row (header first): ranks, blocks, contacts, points, file
 * size, median and each write time (the slowest rank's; from a barrier to
 * the end of the write and of the index), the median time until the file
 * is also on disk (fsync), read time, whether every value read back
 * equals the generator's, and the largest peak RSS of the ranks.
 */
#include <rockdda/dda/hdf5_output.h>

#include <deal.II/base/mpi.h>

#include "../../tests/unit/synthetic_snapshot.h"
#include "../timing.h"
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                           comm = MPI_COMM_WORLD;
  const unsigned int rank  = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  if (argc != 5)
    {
      if (rank == 0)
        std::fprintf(stderr,
                     "usage: mpirun -np N %s COLUMNS COURSES REPEAT FOLDER\n",
                     argv[0]);
      return 1;
    }
  const std::size_t columns = std::stoul(argv[1]),
                    courses = std::stoul(argv[2]);
  const int         repeat  = std::stoi(argv[3]);
  const std::size_t n       = columns * courses;
  const std::size_t first   = n * rank / ranks;
  const std::size_t count   = n * (rank + 1) / ranks - first;

  io::OutputDirectory out(argv[4], rank == 0);
  MPI_Barrier(comm);
  Hdf5Series          series(out, comm);
  std::vector<double> times, durable;
  std::string         name;
  {
    const Snapshot blocks
      = test_scenes::running_bond_blocks(first, count, columns, courses);
    const Snapshot contacts
      = test_scenes::running_bond_contacts(first, count, columns);
    for (int r = 0; r < repeat; ++r)
      {
        MPI_Barrier(comm);
        const auto t0 = std::chrono::steady_clock::now();
        name          = series.write(0.001 * r, blocks, contacts);
        MPI_Barrier(comm);
        times.push_back(benchmarks::seconds_since(t0));
        // Then on disk: rank 0 syncs the file (the write above ends in
        // the page cache; a run does not wait for the disk).
        if (rank == 0)
          {
            const int fd = ::open(out.file(name).c_str(), O_RDONLY);
            if (fd < 0 || ::fsync(fd) != 0)
              std::fprintf(stderr, "cannot sync %s\n", name.c_str());
            if (fd >= 0)
              ::close(fd);
          }
        MPI_Barrier(comm);
        durable.push_back(benchmarks::seconds_since(t0));
      }
  }
  // Rank 0 reads the last snapshot back and compares it with the wall.
  std::string verified   = "yes";
  double      read_s     = 0.;
  std::size_t n_contacts = 0, n_points = 0;
  if (rank == 0)
    {
      const std::string path = out.file(name);
      auto              t0   = std::chrono::steady_clock::now();
      Snapshot          read = read_snapshot_hdf5(path, "blocks");
      read_s                 = benchmarks::seconds_since(t0);
      n_points               = read.n_points();
      std::string difference = test_scenes::first_difference(
        read, test_scenes::running_bond_blocks(0, n, columns, courses));
      t0   = std::chrono::steady_clock::now();
      read = read_snapshot_hdf5(path, "contacts");
      read_s += benchmarks::seconds_since(t0);
      n_contacts = read.n_cells();
      if (difference.empty())
        difference = test_scenes::first_difference(
          read, test_scenes::running_bond_contacts(0, n, columns));
      if (!difference.empty())
        verified = "no: " + difference;
    }
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  const double rss_mib
    = dealii::Utilities::MPI::max(usage.ru_maxrss / 1024., comm);
  if (rank == 0)
    {
      const double mib
        = std::filesystem::file_size(out.file(name)) / (1024. * 1024.);
      std::string all;
      for (const double t : times)
        all += (all.empty() ? "" : " ") + std::to_string(t);
      std::printf("ranks,blocks,contacts,points,MiB,write_s_median,"
                  "write_s_each,MiB_per_s,write_fsync_s_median,read_s,"
                  "verified,peak_rss_MiB\n");
      std::printf("%u,%zu,%zu,%zu,%.1f,%.3f,%s,%.0f,%.3f,%.3f,%s,%.0f\n",
                  ranks,
                  n,
                  n_contacts,
                  n_points,
                  mib,
                  benchmarks::median(times),
                  all.c_str(),
                  mib / benchmarks::median(times),
                  benchmarks::median(durable),
                  read_s,
                  verified.c_str(),
                  rss_mib);
    }
  return verified == "yes" ? 0 : 1;
}
