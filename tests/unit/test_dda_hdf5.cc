/**
 * @file
 * HDF5 + XDMF snapshots of dda (issue 16, item 5): every block's vertices
 * and fields read back with the HDF5 C library, independently of the
 * writer, equal the engine's state; the XDMF indices reference datasets
 * that exist with the dimensions they state; a resumed series continues.
 */
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/vtu_output.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <hdf5.h>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  /// A dataset read with the HDF5 C library: dimensions and values.
  template <typename T>
  struct Dataset
  {
    std::vector<hsize_t> dims;
    std::vector<T>       values;
  };

  template <typename T>
  Dataset<T>
  read(const std::string &file, const std::string &name, const hid_t type)
  {
    Dataset<T>  d;
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    EXPECT_GE(f, 0) << file;
    const hid_t set = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
    EXPECT_GE(set, 0) << name;
    if (set >= 0)
      {
        const hid_t space = H5Dget_space(set);
        d.dims.resize(H5Sget_simple_extent_ndims(space));
        H5Sget_simple_extent_dims(space, d.dims.data(), nullptr);
        std::size_t n = 1;
        for (const auto k : d.dims)
          n *= k;
        d.values.resize(n);
        if (n > 0)
          EXPECT_GE(
            H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()),
            0);
        H5Sclose(space);
        H5Dclose(set);
      }
    H5Fclose(f);
    return d;
  }

  /// A 4 x 5 running-bond wall on a fixed base, pushed sideways.
  BlockSystem
  moving_wall()
  {
    // Far from the origin (UTM-like), as users' scenes are.
    BlockSystem s = running_bond_wall(4, 5, 30., Point(7.1e5, 3.5e6));
    s.gravity     = Point(3., -g_earth);
    return s;
  }
} // namespace



TEST(DdaHdf5, EveryBlockAndFieldReadsBackIntact)
{
  DdaSystem dda(moving_wall(), controls(1e-3, 1., 1e11));
  for (int k = 0; k < 20; ++k)
    dda.step();
  const std::string path
    = (std::filesystem::temp_directory_path() / "rockdda-test-snapshot.h5")
        .string();
  write_snapshot_hdf5(path,
                      dda.time(),
                      blocks_snapshot(dda),
                      contacts_snapshot(dda));

  const auto &scene  = dda.system();
  const auto &blocks = scene.blocks;
  const auto  points = read<double>(path, "/blocks/points", H5T_NATIVE_DOUBLE);
  const auto  topology
    = read<std::int64_t>(path, "/blocks/topology", H5T_NATIVE_INT64);
  const auto displacement
    = read<double>(path, "/blocks/displacement", H5T_NATIVE_DOUBLE);
  const auto stress = read<double>(path, "/blocks/stress", H5T_NATIVE_DOUBLE);
  const auto ids
    = read<std::int32_t>(path, "/blocks/block_id", H5T_NATIVE_INT32);
  ASSERT_EQ(points.dims.size(), 2u);
  EXPECT_EQ(points.dims[1], 3u);
  ASSERT_EQ(ids.values.size(), blocks.size());
  ASSERT_EQ(displacement.dims, (std::vector<hsize_t>{blocks.size(), 3}));
  ASSERT_EQ(stress.dims, (std::vector<hsize_t>{blocks.size(), 6}));
  // Walk the mixed topology: (3, n, n point indices) per block; each
  // point is the block's vertex in global coordinates, bit for bit.
  std::size_t at = 0, n_points = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b)
    {
      const auto &v = blocks[b].polygon.vertices;
      ASSERT_LT(at + 1, topology.values.size());
      EXPECT_EQ(topology.values[at], 3);
      ASSERT_EQ(topology.values[at + 1], static_cast<std::int64_t>(v.size()));
      for (std::size_t k = 0; k < v.size(); ++k)
        {
          const auto p = topology.values[at + 2 + k];
          EXPECT_EQ(points.values[3 * p], scene.origin.x() + v[k].x());
          EXPECT_EQ(points.values[3 * p + 1], scene.origin.y() + v[k].y());
          EXPECT_EQ(points.values[3 * p + 2], 0.);
        }
      n_points += v.size();
      at += 2 + v.size();
      EXPECT_EQ(ids.values[b], blocks[b].id);
      const Point d = dda.centroid_displacement(static_cast<int>(b));
      EXPECT_EQ(displacement.values[3 * b], d.x());
      EXPECT_EQ(displacement.values[3 * b + 1], d.y());
      EXPECT_EQ(stress.values[6 * b], blocks[b].stress[0]);
      EXPECT_EQ(stress.values[6 * b + 1], blocks[b].stress[1]);
      EXPECT_EQ(stress.values[6 * b + 3], blocks[b].stress[2]);
    }
  EXPECT_EQ(at, topology.values.size());
  EXPECT_EQ(points.dims[0], n_points);

  // Contacts: one line per contact, the state and forces as the engine's.
  const auto &contacts = dda.contacts();
  ASSERT_GT(contacts.size(), 10u);
  const auto state
    = read<std::int32_t>(path, "/contacts/state", H5T_NATIVE_INT32);
  const auto fn
    = read<double>(path, "/contacts/normal_force", H5T_NATIVE_DOUBLE);
  const auto lines
    = read<std::int64_t>(path, "/contacts/topology", H5T_NATIVE_INT64);
  ASSERT_EQ(state.values.size(), contacts.size());
  ASSERT_EQ(lines.dims, (std::vector<hsize_t>{contacts.size(), 2}));
  int moving = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c)
    {
      EXPECT_EQ(state.values[c], static_cast<int>(contacts[c].state));
      EXPECT_EQ(fn.values[c], contacts[c].normal_force);
      moving += contacts[c].state == ContactState::sliding;
    }
  // The same fields as the VTU writer (one gathering for both).
  EXPECT_NE(blocks_vtu(dda).find("Name=\"stress\""), std::string::npos);
  std::filesystem::remove(path);
  std::printf("%zu blocks, %zu contacts (%d sliding) read back\n",
              blocks.size(),
              contacts.size(),
              moving);
}



TEST(DdaHdf5, XdmfIndicesMatchTheFilesAndResumeContinues)
{
  const std::string folder
    = (std::filesystem::temp_directory_path() / "rockdda-test-xdmf").string();
  std::filesystem::remove_all(folder);
  DdaSystem   dda(moving_wall(), controls(1e-3, 1., 1e11));
  std::string first_index;
  {
    io::OutputDirectory out(folder);
    Hdf5Series          series(out);
    for (int s = 0; s < 3; ++s)
      {
        for (int k = 0; k < 5; ++k)
          dda.step();
        series.write(dda.time(), blocks_snapshot(dda), contacts_snapshot(dda));
      }
    std::ifstream     in(folder + "/blocks.xdmf");
    std::stringstream text;
    text << in.rdbuf();
    first_index = text.str();
    // A series continued from its file list (a resumed run) writes the
    // same index.
    Hdf5Series resumed(out);
    resumed.restore(series.files());
    std::ifstream     again(folder + "/blocks.xdmf");
    std::stringstream text2;
    text2 << again.rdbuf();
    EXPECT_EQ(text2.str(), first_index);
    EXPECT_THROW(resumed.restore({{0., "blocks-00000.vtu"}}),
                 std::runtime_error);
  }
  // Every DataItem names a dataset that exists with the stated dimensions.
  for (const std::string index : {"blocks.xdmf", "contacts.xdmf"})
    {
      std::ifstream     in(folder + "/" + index);
      std::stringstream text;
      text << in.rdbuf();
      const std::string s = text.str();
      const std::regex  item(
        "<DataItem Dimensions=\"([0-9 ]+)\"[^>]*>([^:<]+):([^<]+)</DataItem>");
      int n_items = 0;
      for (auto it = std::sregex_iterator(s.begin(), s.end(), item);
           it != std::sregex_iterator();
           ++it, ++n_items)
        {
          const auto         data = read<double>(folder + "/" + (*it)[2].str(),
                                         (*it)[3].str(),
                                         H5T_NATIVE_DOUBLE);
          std::ostringstream dims;
          for (std::size_t k = 0; k < data.dims.size(); ++k)
            dims << (k ? " " : "") << data.dims[k];
          EXPECT_EQ(dims.str(), (*it)[1].str()) << index << " " << (*it)[3];
        }
      // 3 snapshots x (topology, geometry and the fields).
      EXPECT_GE(n_items, 3 * 8) << index;
      EXPECT_NE(s.find("CollectionType=\"Temporal\""), std::string::npos);
    }
  std::filesystem::remove_all(folder);
}
