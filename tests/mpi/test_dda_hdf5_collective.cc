/**
 * @file
 * Collective HDF5 snapshots (issue 16, item 5), run on 2 MPI ranks: a
 * 10^4-block running-bond wall split unevenly (and with an empty rank)
 * written by both ranks into one file reads back, through the serial
 * reader, with every block's vertices and fields bit for bit; the file
 * equals the one a single process writes; the XDMF index states the global
 * sizes; ranks passing different fields both throw and leave no file.
 */
#include <rockdda/dda/hdf5_output.h>

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include "../unit/synthetic_snapshot.h"
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <hdf5.h>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  constexpr std::size_t columns = 100, courses = 100;
  constexpr std::size_t n_blocks = columns * courses;

  int
  rank()
  {
    return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  }

  /// A folder shared by the ranks (rank 0's process id in its name).
  std::filesystem::path
  shared_folder(const std::string &name)
  {
    long pid = static_cast<long>(::getpid());
    MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    return std::filesystem::temp_directory_path()
           / ("rockdda-" + name + "-" + std::to_string(pid));
  }

  /// The int64 dataset @p name of @p file.
  std::vector<std::int64_t>
  read_int64(const std::string &file, const std::string &name)
  {
    std::vector<std::int64_t> v;
    const hid_t f   = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t set = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
    if (set >= 0)
      {
        const hid_t space = H5Dget_space(set);
        v.resize(H5Sget_simple_extent_npoints(space));
        H5Dread(set, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
        H5Sclose(space);
        H5Dclose(set);
      }
    H5Fclose(f);
    return v;
  }
} // namespace



TEST(DdaHdf5Collective, TwoRanksWriteEveryBlockIntact)
{
  ASSERT_EQ(dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD), 2u)
    << "run with mpirun -np 2";
  const auto folder = shared_folder("hdf5-collective");
  if (rank() == 0)
    std::filesystem::create_directories(folder);
  MPI_Barrier(MPI_COMM_WORLD);
  const Snapshot blocks   = running_bond_blocks(0, n_blocks, columns, courses);
  const Snapshot contacts = running_bond_contacts(0, n_blocks, columns);
  // The same wall written by one process.
  const std::string serial = (folder / "serial.h5").string();
  if (rank() == 0)
    write_snapshot_hdf5(serial, 0.25, blocks, contacts, MPI_COMM_SELF);

  // Rank 0 owns bricks [0, split), rank 1 the rest: uneven, and empty.
  for (const std::size_t split : {std::size_t(3000), std::size_t(0)})
    {
      SCOPED_TRACE("rank 0 owns " + std::to_string(split) + " bricks");
      const std::size_t   first = rank() == 0 ? 0 : split;
      const std::size_t   count = rank() == 0 ? split : n_blocks - split;
      io::OutputDirectory out((folder / std::to_string(split)).string(),
                              rank() == 0);
      MPI_Barrier(MPI_COMM_WORLD);
      Hdf5Series        series(out, MPI_COMM_WORLD);
      const std::string name
        = series.write(0.25,
                       running_bond_blocks(first, count, columns, courses),
                       running_bond_contacts(first, count, columns));
      // Every rank reads the whole file back with the serial reader.
      const std::string path = out.file(name);
      EXPECT_EQ(first_difference(read_snapshot_hdf5(path, "blocks"), blocks),
                "");
      EXPECT_EQ(first_difference(read_snapshot_hdf5(path, "contacts"),
                                 contacts),
                "");
      EXPECT_EQ(read_snapshot_time(path), 0.25);
      // The topology: per brick (3, n, its n global point indices).
      const auto  topology = read_int64(path, "/blocks/topology");
      std::size_t at = 0, begin = 0;
      bool        intact = topology.size() == 2 * n_blocks + blocks.n_points();
      for (std::size_t b = 0; b < n_blocks && intact; ++b)
        {
          const auto end = static_cast<std::size_t>(blocks.offsets[b]);
          intact
            = topology[at] == 3
              && topology[at + 1] == static_cast<std::int64_t>(end - begin);
          for (std::size_t k = begin; k < end && intact; ++k)
            intact
              = topology[at + 2 + k - begin] == static_cast<std::int64_t>(k);
          at += 2 + end - begin;
          begin = end;
        }
      EXPECT_TRUE(intact) << "blocks topology";
      std::vector<std::int64_t> lines(2 * contacts.n_cells());
      for (std::size_t k = 0; k < lines.size(); ++k)
        lines[k] = static_cast<std::int64_t>(k);
      EXPECT_EQ(read_int64(path, "/contacts/topology"), lines);
      // The same file as one process writes, dataset by dataset.
      for (const char *set : {"/blocks/topology", "/contacts/topology"})
        EXPECT_EQ(read_int64(path, set), read_int64(serial, set)) << set;
      EXPECT_EQ(first_difference(read_snapshot_hdf5(path, "blocks"),
                                 read_snapshot_hdf5(serial, "blocks")),
                "");
      // The index, written by rank 0, states the global sizes.
      MPI_Barrier(MPI_COMM_WORLD);
      std::ifstream      in(out.file("blocks.xdmf"));
      std::ostringstream xdmf;
      xdmf << in.rdbuf();
      const std::string p = std::to_string(blocks.n_points());
      for (const std::string d :
           {std::to_string(2 * n_blocks + blocks.n_points()),
            p + " 3",
            std::to_string(n_blocks) + " 6"})
        EXPECT_NE(xdmf.str().find("Dimensions=\"" + d + "\""),
                  std::string::npos)
          << d;
      EXPECT_NE(xdmf.str().find("NumberType=\"Int\" Precision=\"4\" "
                                "Format=\"HDF\">"
                                + name + ":/blocks/block_id"),
                std::string::npos);
    }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0)
    std::filesystem::remove_all(folder);
}



TEST(DdaHdf5Collective, RanksWithDifferentFieldsAllThrow)
{
  const auto folder = shared_folder("hdf5-disagree");
  if (rank() == 0)
    std::filesystem::create_directories(folder);
  MPI_Barrier(MPI_COMM_WORLD);
  Snapshot blocks = running_bond_blocks(rank() * 10, 10, columns, courses);
  if (rank() == 1)
    blocks.fields.push_back(real_field("extra", 1, std::vector<double>(10)));
  const std::string path = (folder / "s.h5").string();
  try
    {
      write_snapshot_hdf5(path,
                          0.,
                          blocks,
                          running_bond_contacts(rank() * 10, 10, columns),
                          MPI_COMM_WORLD);
      ADD_FAILURE() << "no error on rank " << rank();
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find(path + ":/blocks/"),
                std::string::npos)
        << e.what();
    }
  // No file and no temporary file is left.
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(std::filesystem::is_empty(folder));
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0)
    std::filesystem::remove_all(folder);
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
