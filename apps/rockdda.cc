/**
 * @file
 * The rockdda driver: rockdda [--validate] [--print-parameters] FILE.prm,
 * or mpirun -np N rockdda FILE.prm (the heat analysis then runs
 * distributed; rank 0 writes the results).
 */
#include <rockdda/io/analysis.h>

#include <deal.II/base/mpi.h>

#include <optional>

int
main(int argc, char **argv)
{
  // MPI is initialised (once) only under an MPI launcher; one thread per
  // rank.
  std::optional<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  if (rockdda::io::started_by_mpi_launcher())
    mpi.emplace(argc, argv, 1);
  return rockdda::io::run_driver(argc, argv);
}
