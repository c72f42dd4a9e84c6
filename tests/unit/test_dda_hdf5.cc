/**
 * @file
 * HDF5 + XDMF snapshots of dda (issue 16, item 5): every block's vertices
 * and fields read back with the HDF5 C library, independently of the
 * writer, equal the engine's state; the XDMF indices reference datasets
 * that exist with the dimensions they state; a resumed series continues.
 * statistics.h5 of a run equals its statistics.csv column by column, also
 * after an interrupt and a resume, in 2D (dda) and in 3D (dda3d);
 * measurement_points.h5 holds the measurement point columns of
 * statistics.csv.
 */
#include <rockdda/dda/analyses.h>
#include <rockdda/dda/block_file.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/vtu_output.h>
#include <rockdda/dda3d/analyses.h>
#include <rockdda/io/analysis.h>
#include <rockdda/io/interrupt.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include "test_files.h"
#include <cmath>
#include <csignal>
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

  /// The text of file @p path.
  std::string
  file_text(const std::string &path)
  {
    std::ifstream     in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// The five-block stack of tests/regression (two measurement points)
  /// in the "dda" analysis, 0.2 s in steps of 0.01 s, with HDF5 snapshots
  /// and measurement_points.h5, into @p dir / "out".
  void
  run_stack(const std::filesystem::path &dir,
            const double                 end_time,
            const bool                   resume)
  {
    const std::string prm_text
      = std::string("subsection DDA\n  set Block file = ") + ROCKDDA_SOURCE_DIR
        + "/tests/regression/dda_stack.blocks\n"
          "  set End time = "
        + io::format_number(end_time)
        + "\n  set Time step = 0.01\n"
          "  set Dynamic control = 0.5\n"
          "  set Contact penalty = 1e11\n"
          "  set Output interval = 0.1\n"
          "  set Snapshot format = hdf5\n"
          "  set Measurement point file = hdf5\n"
          "  set Checkpoint interval = 0.05\n"
          "  set Resume = "
        + (resume ? "true" : "false") + "\nend\n";
    auto analyses = make_analyses();
    ASSERT_EQ(analyses.front()->name(), "dda");
    test_files::run_analysis_in(*analyses.front(), dir, prm_text);
  }

  /**
   * statistics.h5 in @p folder equals statistics.csv: read with the HDF5
   * C library, every column (a dataset named by the column's name, with
   * its unit) equals the CSV's values to its 12 printed digits, and the
   * table read back prints the same CSV, byte for byte. Returns the
   * number of rows.
   */
  std::size_t
  expect_statistics_match(const std::string &folder)
  {
    const std::string csv  = file_text(folder + "/statistics.csv");
    const std::string h5   = folder + "/statistics.h5";
    const io::Table   back = read_table_hdf5(h5);
    EXPECT_EQ(back.csv(), csv);
    std::istringstream       in(csv);
    std::string              line;
    std::vector<std::string> header;
    std::getline(in, line);
    header = io::split_csv_record(line);
    std::vector<std::vector<double>> columns(header.size());
    while (std::getline(in, line))
      {
        const auto fields = io::split_csv_record(line);
        EXPECT_EQ(fields.size(), header.size());
        for (std::size_t k = 0; k < fields.size() && k < header.size(); ++k)
          columns[k].push_back(std::stod(fields[k]));
      }
    EXPECT_EQ(back.n_columns(), header.size());
    for (std::size_t k = 0; k < back.n_columns() && k < header.size(); ++k)
      {
        const std::string &name = back.column_name(k);
        const std::string &unit = back.column_unit(k);
        EXPECT_EQ(unit == "-"
                    ? name
                    : name + "_"
                        + std::regex_replace(
                          std::regex_replace(unit, std::regex("/"), "_"),
                          std::regex("\\^"),
                          "p"),
                  header[k]);
        const auto d = read<double>(h5, name, H5T_NATIVE_DOUBLE);
        EXPECT_EQ(d.dims.size(), 1u) << name;
        EXPECT_EQ(d.values.size(), columns[k].size()) << name;
        for (std::size_t i = 0; i < d.values.size() && i < columns[k].size();
             ++i)
          EXPECT_LE(std::abs(d.values[i] - columns[k][i]),
                    5e-12 * std::abs(columns[k][i]))
            << name << " row " << i;
      }
    return columns.empty() ? 0 : columns.front().size();
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
    first_index = test_files::read_file(folder + "/blocks.xdmf");
    // A series continued from its file list (a resumed run) writes the
    // same index.
    Hdf5Series resumed(out);
    resumed.restore(series.files());
    EXPECT_EQ(test_files::read_file(folder + "/blocks.xdmf"), first_index);
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



TEST(DdaHdf5, StatisticsH5EqualsTheCsvAlsoAfterAnInterruptAndResume)
{
  const auto full = test_files::scratch("statistics-h5-full");
  run_stack(full, 0.2, false);
  const std::string out = (full / "out").string();
  // 0.2 s in steps of 0.01 s: the row at t = 0 and one per step.
  EXPECT_EQ(expect_statistics_match(out), 21u);

  // measurement_points.h5: the measurement point columns of the CSV.
  const io::Table stats  = read_table_hdf5(out + "/statistics.h5");
  const auto      points = read_series_hdf5(out + "/measurement_points.h5");
  const auto      mps    = read_block_file(std::string(ROCKDDA_SOURCE_DIR)
                                   + "/tests/regression/dda_stack.blocks")
                     .measurement_points;
  ASSERT_EQ(mps.size(), 2u);
  const std::vector<std::pair<std::string, std::string>> expected{
    {"time", "s"},
    {"ux", "m"},
    {"uy", "m"},
    {"sigma_x", "Pa"},
    {"sigma_y", "Pa"},
    {"tau_xy", "Pa"},
    {"initial_position", "m"}};
  ASSERT_EQ(points.size(), expected.size());
  for (std::size_t q = 0; q < expected.size(); ++q)
    {
      EXPECT_EQ(points[q].name, expected[q].first);
      EXPECT_EQ(points[q].unit, expected[q].second);
    }
  for (std::size_t c = 0; c < stats.n_columns(); ++c)
    for (std::size_t m = 0; m < mps.size(); ++m)
      for (std::size_t q = 1; q <= 5; ++q)
        if (stats.column_name(c)
            == "mp" + std::to_string(m + 1) + "_" + expected[q].first)
          {
            EXPECT_EQ(points[q].components, mps.size());
            for (std::size_t i = 0; i < stats.n_rows(); ++i)
              EXPECT_EQ(points[q].values[i * mps.size() + m], stats.row(i)[c]);
          }
  for (std::size_t i = 0; i < stats.n_rows(); ++i)
    EXPECT_EQ(points[0].values[i], stats.row(i)[0]);
  for (std::size_t m = 0; m < mps.size(); ++m)
    {
      // The block file's coordinates.
      EXPECT_DOUBLE_EQ(points[6].values[2 * m], mps[m].point.x());
      EXPECT_DOUBLE_EQ(points[6].values[2 * m + 1], mps[m].point.y());
    }
  // The top block settles: its point moves down.
  EXPECT_LT(points[2].values.back(), 0.);

  // A run stopped by SIGTERM before its first step keeps statistics.h5
  // with the rows so far (t = 0), equal to its CSV; resumed to the end,
  // it equals the uninterrupted run.
  const auto part = test_files::scratch("statistics-h5-part");
  {
    io::InterruptGuard guard;
    std::raise(SIGTERM);
    run_stack(part, 0.2, false);
    io::clear_interrupt();
  }
  const std::string part_out = (part / "out").string();
  EXPECT_EQ(expect_statistics_match(part_out), 1u);
  run_stack(part, 0.2, true);
  EXPECT_EQ(expect_statistics_match(part_out), 21u);
  EXPECT_EQ(read_table_hdf5(part_out + "/statistics.h5").csv(), stats.csv());
  EXPECT_EQ(read_series_hdf5(part_out + "/measurement_points.h5")[2].values,
            points[2].values);

  // A write that fails half way (a killed run) leaves the file of the
  // last flush intact and no temporary file.
  const io::OutputDirectory dir(part_out);
  EXPECT_THROW(
    dir.write_with("statistics.h5",
                   [&](const std::string &tmp) {
                     write_series_hdf5(tmp, {{"time", "s", 1, {0.}}});
                     throw std::runtime_error("killed");
                   }),
    std::runtime_error);
  EXPECT_EQ(read_table_hdf5(part_out + "/statistics.h5").csv(), stats.csv());
  for (const auto &f : std::filesystem::directory_iterator(part_out))
    EXPECT_EQ(f.path().string().find(".tmp."), std::string::npos) << f.path();
}



TEST(DdaHdf5, Dda3dStatisticsH5EqualsTheCsvAlsoAfterAResume)
{
  // The cube sliding down a 30 deg plane of tests/regression (one
  // measurement point on the cube), 0.2 s in steps of 5 ms, checkpoints
  // every 0.05 s, 'Snapshot format' = hdf5 as in 2D.
  const auto prm_text = [](const double end_time, const bool resume) {
    return std::string("subsection DDA 3d\n  set Block file = ")
           + ROCKDDA_SOURCE_DIR
           + "/tests/regression/dda3d_incline.blocks\n"
             "  set End time = "
           + io::format_number(end_time)
           + "\n  set Time step = 0.005\n"
             "  set Contact penalty = 1e11\n"
             "  set Output interval = 0.1\n"
             "  set Snapshot format = hdf5\n"
             "  set Checkpoint interval = 0.05\n"
             "  set Resume = "
           + (resume ? "true" : "false") + "\nend\n";
  };
  const auto run
    = [](const std::filesystem::path &dir, const std::string &text) {
        auto analyses = dda3d::make_analyses();
        ASSERT_EQ(analyses.front()->name(), "dda3d");
        test_files::run_analysis_in(*analyses.front(), dir, text);
      };
  const auto full = test_files::scratch("statistics-h5-3d-full");
  run(full, prm_text(0.2, false));
  const std::string out = (full / "out").string();
  // The row at t = 0 and one per step of 5 ms at least.
  EXPECT_GE(expect_statistics_match(out), 41u);
  // The 3D snapshots are HDF5 too (each block as its faces): one at t =
  // 0, 0.1 and 0.2 s, indexed by blocks.xdmf and contacts.xdmf; no VTU.
  for (const char *f : {"/blocks.xdmf",
                        "/contacts.xdmf",
                        "/snapshot-00000.h5",
                        "/snapshot-00001.h5",
                        "/snapshot-00002.h5"})
    EXPECT_TRUE(std::filesystem::exists(out + f)) << f;
  EXPECT_FALSE(std::filesystem::exists(out + "/blocks.pvd"));
  EXPECT_FALSE(std::filesystem::exists(out + "/snapshot-00003.h5"));

  // The file holds the physics of the CSV's columns: the point on the cube
  // moves along the dip as d = g/2 (sin 30 - cos 30 tan 20) t^2, ux = d cos
  // 30 and uz = -d sin 30 (tests/regression/dda3d_incline.prm), within
  // 0.1 % of d at t = 0.2 s (the engine's error at this time step is 7.5e-5
  // of d at 1 s: tests/regression/dda3d_incline.ref).
  const io::Table stats = read_table_hdf5(out + "/statistics.h5");
  std::size_t     ux = stats.n_columns(), uz = ux;
  for (std::size_t c = 0; c < stats.n_columns(); ++c)
    {
      if (stats.column_name(c) == "mp1_ux")
        ux = c;
      if (stats.column_name(c) == "mp1_uz")
        uz = c;
    }
  ASSERT_LT(ux, stats.n_columns());
  ASSERT_LT(uz, stats.n_columns());
  const auto  &last = stats.row(stats.n_rows() - 1);
  const double pi = std::acos(-1.), t = last[0], c30 = std::cos(pi / 6),
               d = 0.5 * 9.80665 * (0.5 - c30 * std::tan(pi / 9)) * t * t;
  EXPECT_DOUBLE_EQ(t, 0.2);
  EXPECT_NEAR(last[ux], d * c30, 1e-3 * d);
  EXPECT_NEAR(last[uz], -0.5 * d, 1e-3 * d);

  // Run to 0.1 s (checkpoint), then resumed to 0.2 s: the same file.
  const auto part = test_files::scratch("statistics-h5-3d-part");
  run(part, prm_text(0.1, false));
  const std::string part_out = (part / "out").string();
  EXPECT_EQ(expect_statistics_match(part_out), 21u);
  run(part, prm_text(0.2, true));
  expect_statistics_match(part_out);
  EXPECT_EQ(read_table_hdf5(part_out + "/statistics.h5").csv(), stats.csv());
  // The resumed run continues the snapshot series: the same index and the
  // same last snapshot, bit for bit.
  EXPECT_EQ(test_files::read_file(part_out + "/blocks.xdmf"),
            test_files::read_file(out + "/blocks.xdmf"));
  const Snapshot a = read_snapshot_hdf5(out + "/snapshot-00002.h5", "blocks");
  const Snapshot b
    = read_snapshot_hdf5(part_out + "/snapshot-00002.h5", "blocks");
  EXPECT_EQ(a.xyz, b.xyz);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t k = 0; k < a.fields.size(); ++k)
    EXPECT_EQ(a.fields[k].real, b.fields[k].real) << a.fields[k].name;
}



TEST(DdaHdf5, SeriesFileRoundTripAndBadShapes)
{
  const auto                       dir  = test_files::scratch("series-h5");
  const std::string                path = (dir / "s.h5").string();
  const std::vector<SeriesDataset> sets{{"time", "s", 1, {0., 0.5, 1.}},
                                        {"uy", "m", 2, {1, 2, 3, 4, 5, 6}},
                                        {"empty", "Pa", 3, {}}};
  write_series_hdf5(path, sets);
  const auto back = read_series_hdf5(path);
  ASSERT_EQ(back.size(), sets.size());
  for (std::size_t k = 0; k < sets.size(); ++k)
    {
      EXPECT_EQ(back[k].name, sets[k].name);
      EXPECT_EQ(back[k].unit, sets[k].unit);
      EXPECT_EQ(back[k].values, sets[k].values);
      if (!sets[k].values.empty())
        {
          EXPECT_EQ(back[k].components, sets[k].components);
        }
    }
  const auto uy = read<double>(path, "uy", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(uy.dims, (std::vector<hsize_t>{3, 2}));
  EXPECT_THROW(write_series_hdf5(path, {{"uy", "m", 2, {1., 2., 3.}}}),
               std::runtime_error);
  EXPECT_THROW(read_series_hdf5((dir / "missing.h5").string()),
               std::runtime_error);
}



TEST(DdaHdf5, LayeringStudyWritesTheMeasurementPointFile)
{
  // The DDA controls of every model of the layering study
  // (benchmarks/layering-chapter-3) ask for measurement_points.h5.
  dealii::ParameterHandler prm;
  io::declare_all_parameters(prm, io::all_analyses());
  prm.parse_input(std::string(ROCKDDA_SOURCE_DIR)
                  + "/parameter-files/layering/table-3-2.prm");
  prm.enter_subsection("DDA");
  EXPECT_EQ(prm.get("Measurement point file"), "hdf5");
  prm.leave_subsection();
}
