/**
 * @file
 * HDF5 snapshots and XDMF indices of a DDA run (the HDF5 C library that
 * deal.II links).
 */
#include <rockdda/dda/hdf5_output.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <hdf5.h>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace rockdda::dda
{
  namespace
  {
    /// An HDF5 handle closed on scope exit.
    class Handle
    {
    public:
      Handle(const hid_t id, herr_t (*close)(hid_t), const std::string &what)
          : id(id)
          , close(close)
      {
        if (id < 0)
          throw std::runtime_error("HDF5: cannot " + what);
      }
      ~Handle()
      {
        close(id);
      }
      Handle(const Handle &) = delete;
      Handle &
      operator=(const Handle &)
        = delete;
      operator hid_t() const
      {
        return id;
      }

    private:
      hid_t id;
      herr_t (*close)(hid_t);
    };

    void
    check(const herr_t status, const std::string &what)
    {
      if (status < 0)
        throw std::runtime_error("HDF5: cannot " + what);
    }

    /// The ranks of a collective write (one, without MPI initialised).
    struct Ranks
    {
      Ranks(const MPI_Comm comm, const std::string &path)
          : comm(comm)
      {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (initialised)
          {
            MPI_Comm_rank(comm, &rank);
            MPI_Comm_size(comm, &size);
          }
        else if (comm != MPI_COMM_SELF)
          throw std::runtime_error("HDF5: cannot write " + path
                                   + " over MPI ranks: MPI is not initialised");
      }

      /// Elementwise maximum of @p v over the ranks.
      void
      max(std::vector<std::uint64_t> &v) const
      {
        if (size > 1)
          MPI_Allreduce(MPI_IN_PLACE,
                        v.data(),
                        static_cast<int>(v.size()),
                        MPI_UINT64_T,
                        MPI_MAX,
                        comm);
      }

      MPI_Comm comm;
      int      rank = 0, size = 1;
    };

    /// Where one rank's rows go in a dataset of all ranks' rows.
    struct Rows
    {
      hsize_t local = 0, offset = 0, total = 0;
    };

    /**
     * Create dataset @p name of @p rows.total rows of @p columns values (0:
     * a 1-D dataset) and write this rank's @p rows.local rows @p values at
     * row @p rows.offset with the transfer list @p transfer (collective:
     * every rank calls it, with or without rows).
     */
    template <typename T>
    void
    write_rows(const hid_t        group,
               const std::string &name,
               const hid_t        type,
               const T           *values,
               const Rows        &rows,
               const hsize_t      columns,
               const hid_t        transfer,
               const std::string &where)
    {
      const int     rank     = columns > 0 ? 2 : 1;
      const hsize_t dims[2]  = {rows.total, columns};
      const hsize_t start[2] = {rows.offset, 0};
      const hsize_t count[2] = {rows.local, columns};
      const Handle  space(H5Screate_simple(rank, dims, nullptr),
                         H5Sclose,
                         "create a dataspace for " + where + name);
      const Handle  set(H5Dcreate2(group,
                                  name.c_str(),
                                  type,
                                  space,
                                  H5P_DEFAULT,
                                  H5P_DEFAULT,
                                  H5P_DEFAULT),
                       H5Dclose,
                       "create dataset " + where + name);
      if (rows.total == 0)
        return;
      // A rank without rows selects nothing in the file and in a one-row
      // memory space, and still takes part in the collective write.
      const hsize_t one[2] = {std::max<hsize_t>(rows.local, 1), columns};
      const Handle  memory(H5Screate_simple(rank, one, nullptr),
                          H5Sclose,
                          "create a memory dataspace for " + where + name);
      if (rows.local > 0)
        check(H5Sselect_hyperslab(
                space, H5S_SELECT_SET, start, nullptr, count, nullptr),
              "select rows of " + where + name);
      else
        {
          check(H5Sselect_none(space), "select rows of " + where + name);
          check(H5Sselect_none(memory), "select rows of " + where + name);
        }
      const T none[6] = {};
      check(
        H5Dwrite(
          set, type, memory, space, transfer, rows.local > 0 ? values : none),
        "write dataset " + where + name);
    }

    /// Dimensions of a dataset.
    std::vector<hsize_t>
    dimensions(const hid_t set, const std::string &what)
    {
      const Handle space(H5Dget_space(set), H5Sclose, "read " + what);
      const int    rank = H5Sget_simple_extent_ndims(space);
      if (rank < 0)
        throw std::runtime_error("HDF5: cannot read the rank of " + what);
      std::vector<hsize_t> dims(rank);
      H5Sget_simple_extent_dims(space, dims.data(), nullptr);
      return dims;
    }

    template <typename T>
    std::vector<T>
    read_dataset(const hid_t        group,
                 const std::string &name,
                 const hid_t        type,
                 const std::string &where,
                 std::size_t       *columns = nullptr)
    {
      const Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT),
                       H5Dclose,
                       "open dataset " + where + name);
      const auto   dims = dimensions(set, where + name);
      std::size_t  n    = 1;
      for (const auto d : dims)
        n *= d;
      if (columns != nullptr)
        *columns = dims.size() > 1 ? dims[1] : 1;
      std::vector<T> values(n);
      if (n > 0)
        check(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
              "read dataset " + where + name);
      return values;
    }

    /**
     * Check that every rank passes the same fields for group @p name and
     * that its arrays have consistent sizes (every rank throws otherwise,
     * before any collective HDF5 call), and return the group's layout over
     * all ranks and this rank's first cell and point.
     */
    std::pair<SnapshotLayout, std::pair<std::uint64_t, std::uint64_t>>
    agree(const Ranks &ranks, const Snapshot &s, const std::string &where)
    {
      std::string signature = s.lines ? "lines;" : "polygons;";
      bool        consistent
        = s.xyz.size() % 3 == 0
          && (s.offsets.empty()
              || s.offsets.back() == static_cast<std::int64_t>(s.n_points()));
      for (const auto &f : s.fields)
        {
          signature += f.name + ":" + std::to_string(f.components) + ";";
          consistent
            = consistent && f.components > 0
              && (f.integer.empty() || f.real.empty())
              && f.size() == s.n_cells()
              && (f.integer.empty() ? f.real.size() : f.integer.size())
                   == s.n_cells() * static_cast<std::size_t>(f.components);
        }
      const std::uint64_t hash = std::hash<std::string>()(signature);
      // Maxima of: hash and its complement (equal hashes on every rank),
      // inconsistency, and per field whether it holds integers and reals.
      std::vector<std::uint64_t> flags = {hash, ~hash, consistent ? 0u : 1u};
      for (const auto &f : s.fields)
        {
          flags.push_back(f.integer.empty() ? 0 : 1);
          flags.push_back(f.real.empty() ? 0 : 1);
        }
      if (ranks.size > 1)
        {
          std::vector<std::uint64_t> length = {flags.size(), ~flags.size()};
          ranks.max(length);
          if (length[0] != ~length[1])
            throw std::runtime_error("HDF5: the MPI ranks write different "
                                     "fields into "
                                     + where);
        }
      ranks.max(flags);
      if (flags[0] != ~flags[1])
        throw std::runtime_error("HDF5: the MPI ranks write different fields "
                                 "(names or components) into "
                                 + where);
      if (flags[2] != 0)
        throw std::runtime_error(
          "HDF5: inconsistent snapshot for " + where
          + " on some rank (3 coordinates per point, the last offset equal to "
            "the number of points, one value per cell and component)");
      SnapshotLayout layout;
      for (std::size_t k = 0; k < s.fields.size(); ++k)
        {
          if (flags[3 + 2 * k] != 0 && flags[4 + 2 * k] != 0)
            throw std::runtime_error("HDF5: field " + s.fields[k].name + " of "
                                     + where
                                     + " is integer on some MPI ranks and "
                                       "real on others");
          layout.integer.push_back(flags[3 + 2 * k] != 0);
        }
      // First cell and point of this rank, and the totals.
      std::uint64_t local[2] = {s.n_cells(), s.n_points()};
      std::uint64_t first[2] = {0, 0}, total[2] = {local[0], local[1]};
      if (ranks.size > 1)
        {
          MPI_Exscan(local, first, 2, MPI_UINT64_T, MPI_SUM, ranks.comm);
          if (ranks.rank == 0)
            first[0] = first[1] = 0;
          MPI_Allreduce(local, total, 2, MPI_UINT64_T, MPI_SUM, ranks.comm);
        }
      layout.cells  = total[0];
      layout.points = total[1];
      return {layout, {first[0], first[1]}};
    }

    SnapshotLayout
    write_group(const hid_t        file,
                const std::string &name,
                const Snapshot    &s,
                const std::string &path,
                const Ranks       &ranks,
                const hid_t        transfer)
    {
      const std::string where    = path + ":/" + name + "/";
      const auto [layout, first] = agree(ranks, s, where);
      const auto [cell0, point0] = first;
      // The fields are listed in the order written (read_snapshot_hdf5).
      const Handle order(H5Pcreate(H5P_GROUP_CREATE),
                         H5Pclose,
                         "create a property list for " + where);
      check(H5Pset_link_creation_order(order,
                                       H5P_CRT_ORDER_TRACKED
                                         | H5P_CRT_ORDER_INDEXED),
            "track the creation order in " + where);
      const Handle group(
        H5Gcreate2(file, name.c_str(), H5P_DEFAULT, order, H5P_DEFAULT),
        H5Gclose,
        "create group " + where);
      const hsize_t n = s.n_cells();
      const Rows    cells{n, cell0, layout.cells};
      write_rows(group,
                 "points",
                 H5T_NATIVE_DOUBLE,
                 s.xyz.data(),
                 Rows{s.n_points(), point0, layout.points},
                 3,
                 transfer,
                 where);
      // Point indices are global: shifted by the points of lower ranks.
      const auto                shift = static_cast<std::int64_t>(point0);
      std::vector<std::int64_t> offsets(s.offsets);
      for (auto &o : offsets)
        o += shift;
      write_rows(group,
                 "offsets",
                 H5T_NATIVE_INT64,
                 offsets.data(),
                 cells,
                 0,
                 transfer,
                 where);
      offsets = {};
      std::vector<std::int64_t> topology;
      if (s.lines)
        {
          topology.resize(s.n_points());
          for (std::size_t k = 0; k < topology.size(); ++k)
            topology[k] = shift + static_cast<std::int64_t>(k);
          write_rows(group,
                     "topology",
                     H5T_NATIVE_INT64,
                     topology.data(),
                     cells,
                     2,
                     transfer,
                     where);
        }
      else
        {
          // Per cell (3, number of points, the point indices): 2 cells +
          // points values before this rank's.
          topology.reserve(2 * n + s.n_points());
          std::int64_t begin = 0;
          for (const auto end : s.offsets)
            {
              topology.push_back(3); // XDMF polygon
              topology.push_back(end - begin);
              for (std::int64_t k = begin; k < end; ++k)
                topology.push_back(shift + k);
              begin = end;
            }
          write_rows(group,
                     "topology",
                     H5T_NATIVE_INT64,
                     topology.data(),
                     Rows{topology.size(),
                          2 * cell0 + point0,
                          2 * layout.cells + layout.points},
                     0,
                     transfer,
                     where);
        }
      topology = {};
      for (std::size_t k = 0; k < s.fields.size(); ++k)
        {
          const auto   &f = s.fields[k];
          const hsize_t columns
            = f.components > 1 ? static_cast<hsize_t>(f.components) : 0;
          if (layout.integer[k])
            write_rows(group,
                       f.name,
                       H5T_NATIVE_INT32,
                       f.integer.data(),
                       cells,
                       columns,
                       transfer,
                       where);
          else
            write_rows(group,
                       f.name,
                       H5T_NATIVE_DOUBLE,
                       f.real.data(),
                       cells,
                       columns,
                       transfer,
                       where);
        }
      return layout;
    }

    /// The names of the links in @p group, in the order created (the
    /// group tracks it).
    std::vector<std::string>
    names_in_order(const hid_t group, const std::string &where)
    {
      H5G_info_t info;
      check(H5Gget_info(group, &info), "list " + where);
      std::vector<std::string> names;
      for (hsize_t k = 0; k < info.nlinks; ++k)
        {
          char name[256];
          if (H5Lget_name_by_idx(group,
                                 ".",
                                 H5_INDEX_CRT_ORDER,
                                 H5_ITER_INC,
                                 k,
                                 name,
                                 sizeof(name),
                                 H5P_DEFAULT)
              < 0)
            throw std::runtime_error("HDF5: cannot list " + where);
          names.emplace_back(name);
        }
      return names;
    }

    /// Attach the string attribute @p name = @p value to @p object.
    void
    write_string_attribute(const hid_t        object,
                           const std::string &name,
                           const std::string &value,
                           const std::string &where)
    {
      const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
      check(H5Tset_size(type, std::max<std::size_t>(value.size(), 1)),
            "size a string type for " + where);
      const Handle space(H5Screate(H5S_SCALAR),
                         H5Sclose,
                         "create a dataspace for " + where);
      const Handle attribute(
        H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose,
        "create attribute " + name + " of " + where);
      check(H5Awrite(attribute, type, value.c_str()),
            "write attribute " + name + " of " + where);
    }

    /// The string attribute @p name of @p object.
    std::string
    read_string_attribute(const hid_t        object,
                          const std::string &name,
                          const std::string &where)
    {
      const Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT),
                             H5Aclose,
                             "open attribute " + name + " of " + where);
      const Handle type(H5Aget_type(attribute),
                        H5Tclose,
                        "read the type of attribute " + name + " of " + where);
      if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0)
        throw std::runtime_error("HDF5: attribute " + name + " of " + where
                                 + " is not a fixed-length string");
      std::string value(H5Tget_size(type), '\0');
      check(H5Aread(attribute, type, value.data()),
            "read attribute " + name + " of " + where);
      return value.substr(0, value.find('\0'));
    }

    /// The layout of a snapshot held by one process (as read back).
    SnapshotLayout
    layout_of(const Snapshot &s)
    {
      SnapshotLayout layout;
      layout.cells  = s.n_cells();
      layout.points = s.n_points();
      for (const auto &f : s.fields)
        layout.integer.push_back(!f.integer.empty());
      return layout;
    }

    /// The XDMF <Grid> of one group of one snapshot.
    std::string
    grid(const double          time,
         const std::string    &file,
         const std::string    &group,
         const Snapshot       &s,
         const SnapshotLayout &layout)
    {
      const std::string  h5 = file + ":/" + group + "/";
      std::ostringstream x;
      x << std::setprecision(12);
      const std::uint64_t n = layout.cells, n_points = layout.points;
      x << "   <Grid Name=\"" << group << "\" GridType=\"Uniform\">\n"
        << "    <Time Value=\"" << time << "\"/>\n";
      if (s.lines)
        x << "    <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" "
             "NumberOfElements=\""
          << n << "\">\n     <DataItem Dimensions=\"" << n
          << " 2\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5
          << "topology</DataItem>\n    </Topology>\n";
      else
        x << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << n
          << "\">\n     <DataItem Dimensions=\"" << 2 * n + n_points
          << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5
          << "topology</DataItem>\n    </Topology>\n";
      x << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\""
        << n_points
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
        << "points</DataItem>\n    </Geometry>\n";
      for (std::size_t k = 0; k < s.fields.size(); ++k)
        {
          const auto &f       = s.fields[k];
          const bool  integer = layout.integer[k];
          const char *kind    = f.components == 1   ? "Scalar"
                                : f.components == 3 ? "Vector"
                                                    : "Matrix";
          x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\""
            << kind << "\" Center=\"Cell\">\n     <DataItem Dimensions=\"" << n;
          if (f.components > 1)
            x << " " << f.components;
          x << "\" NumberType=\"" << (integer ? "Int" : "Float")
            << "\" Precision=\"" << (integer ? 4 : 8) << "\" Format=\"HDF\">"
            << h5 << f.name << "</DataItem>\n    </Attribute>\n";
        }
      x << "   </Grid>\n";
      return x.str();
    }

    std::string
    index(const std::string &name, const std::vector<std::string> &grids)
    {
      std::string x = "<?xml version=\"1.0\" ?>\n"
                      "<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\""
                      + name
                      + "\" GridType=\"Collection\" "
                        "CollectionType=\"Temporal\">\n";
      for (const auto &g : grids)
        x += g;
      x += "  </Grid>\n </Domain>\n</Xdmf>\n";
      return x;
    }
  } // namespace



  std::pair<SnapshotLayout, SnapshotLayout>
  write_snapshot_hdf5(const std::string &path,
                      const double       time,
                      const Snapshot    &blocks,
                      const Snapshot    &contacts,
                      const MPI_Comm     comm)
  {
    const Ranks ranks(comm, path);
    // One temporary name on every rank: rank 0's process id.
    long pid = static_cast<long>(::getpid());
    if (ranks.size > 1)
      MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
    const std::string tmp = path + ".tmp." + std::to_string(pid);
    std::pair<SnapshotLayout, SnapshotLayout> layouts;
    try
      {
        const Handle access(H5Pcreate(H5P_FILE_ACCESS),
                            H5Pclose,
                            "create a file access list for " + path);
        const Handle transfer(H5Pcreate(H5P_DATASET_XFER),
                              H5Pclose,
                              "create a transfer list for " + path);
        if (ranks.size > 1)
          {
#ifdef H5_HAVE_PARALLEL
            check(H5Pset_fapl_mpio(access, comm, MPI_INFO_NULL),
                  "select MPI-IO for " + path);
            check(H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE),
                  "select collective transfers for " + path);
#else
            throw std::runtime_error(
              "HDF5: cannot write " + path
              + " from several MPI ranks: the HDF5 library is serial");
#endif
          }
        const Handle file(
          H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access),
          H5Fclose,
          "create " + tmp);
        {
          const Handle space(H5Screate(H5S_SCALAR),
                             H5Sclose,
                             "create a dataspace in " + path);
          const Handle attribute(
            H5Acreate2(
              file, "time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose,
            "create attribute time in " + path);
          check(H5Awrite(attribute, H5T_NATIVE_DOUBLE, &time),
                "write attribute time in " + path);
        }
        layouts.first
          = write_group(file, "blocks", blocks, path, ranks, transfer);
        layouts.second
          = write_group(file, "contacts", contacts, path, ranks, transfer);
      }
    catch (...)
      {
        if (ranks.rank == 0)
          std::remove(tmp.c_str());
        throw;
      }
    // Every rank has closed the file: rank 0 renames it into place and
    // tells the others whether it could.
    int renamed = 1;
    if (ranks.size > 1)
      MPI_Barrier(comm);
    std::error_code ec;
    if (ranks.rank == 0)
      {
        std::filesystem::rename(tmp, path, ec);
        renamed = ec ? 0 : 1;
        if (ec)
          std::remove(tmp.c_str());
      }
    if (ranks.size > 1)
      MPI_Bcast(&renamed, 1, MPI_INT, 0, comm);
    if (renamed == 0)
      throw std::runtime_error("cannot rename " + tmp + " to " + path
                               + (ec ? ": " + ec.message() : std::string()));
    return layouts;
  }



  double
  read_snapshot_time(const std::string &path)
  {
    const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                      H5Fclose,
                      "open " + path);
    const Handle attribute(H5Aopen(file, "time", H5P_DEFAULT),
                           H5Aclose,
                           "open attribute time in " + path);
    double       time = 0.;
    check(H5Aread(attribute, H5T_NATIVE_DOUBLE, &time),
          "read attribute time in " + path);
    return time;
  }



  Snapshot
  read_snapshot_hdf5(const std::string &path, const std::string &group_name)
  {
    const Handle      file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                      H5Fclose,
                      "open " + path);
    const std::string where = path + ":/" + group_name + "/";
    const Handle      group(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT),
                       H5Gclose,
                       "open group " + where);
    Snapshot          s;
    s.lines = group_name == "contacts";
    s.xyz   = read_dataset<double>(group, "points", H5T_NATIVE_DOUBLE, where);
    s.offsets
      = read_dataset<std::int64_t>(group, "offsets", H5T_NATIVE_INT64, where);
    // The fields: every other dataset, in the order written.
    for (const std::string &n : names_in_order(group, where))
      {
        const char *name = n.c_str();
        if (n == "points" || n == "offsets" || n == "topology")
          continue;
        SnapshotField f;
        f.name = n;
        const Handle set(H5Dopen2(group, name, H5P_DEFAULT),
                         H5Dclose,
                         "open dataset " + where + n);
        const Handle type(H5Dget_type(set), H5Tclose, "read type of " + n);
        std::size_t  columns = 1;
        if (H5Tget_class(type) == H5T_INTEGER)
          f.integer = read_dataset<std::int32_t>(
            group, n, H5T_NATIVE_INT32, where, &columns);
        else
          f.real = read_dataset<double>(
            group, n, H5T_NATIVE_DOUBLE, where, &columns);
        f.components = static_cast<int>(columns);
        s.fields.push_back(std::move(f));
      }
    return s;
  }



  void
  write_series_hdf5(const std::string                &path,
                    const std::vector<SeriesDataset> &datasets)
  {
    // The datasets are listed in the order written (read_series_hdf5).
    const Handle order(H5Pcreate(H5P_FILE_CREATE),
                       H5Pclose,
                       "create a property list for " + path);
    check(H5Pset_link_creation_order(order,
                                     H5P_CRT_ORDER_TRACKED
                                       | H5P_CRT_ORDER_INDEXED),
          "track the creation order in " + path);
    const Handle file(
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, order, H5P_DEFAULT),
      H5Fclose,
      "create " + path);
    const std::string where = path + ":/";
    for (const auto &d : datasets)
      {
        const hsize_t columns = d.components > 1 ? d.components : 0;
        const hsize_t rows
          = d.values.size() / std::max<std::size_t>(d.components, 1);
        if (d.components == 0 || rows * d.components != d.values.size())
          throw std::runtime_error("HDF5: dataset " + where + d.name + " has "
                                   + std::to_string(d.values.size())
                                   + " values, not a multiple of its "
                                   + std::to_string(d.components)
                                   + " components");
        write_rows(file,
                   d.name,
                   H5T_NATIVE_DOUBLE,
                   d.values.data(),
                   Rows{rows, 0, rows},
                   columns,
                   H5P_DEFAULT,
                   where);
        const Handle set(H5Dopen2(file, d.name.c_str(), H5P_DEFAULT),
                         H5Dclose,
                         "open dataset " + where + d.name);
        write_string_attribute(set, "unit", d.unit, where + d.name);
      }
  }



  std::vector<SeriesDataset>
  read_series_hdf5(const std::string &path)
  {
    const Handle      file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                      H5Fclose,
                      "open " + path);
    const std::string where = path + ":/";
    std::vector<SeriesDataset> datasets;
    for (const std::string &name : names_in_order(file, where))
      {
        SeriesDataset d;
        d.name   = name;
        d.values = read_dataset<double>(
          file, d.name, H5T_NATIVE_DOUBLE, where, &d.components);
        const Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT),
                         H5Dclose,
                         "open dataset " + where + d.name);
        d.unit = read_string_attribute(set, "unit", where + d.name);
        datasets.push_back(std::move(d));
      }
    return datasets;
  }



  void
  write_table_hdf5(const io::OutputDirectory &output,
                   const std::string         &name,
                   const io::Table           &table)
  {
    std::vector<SeriesDataset> columns(table.n_columns());
    for (std::size_t k = 0; k < columns.size(); ++k)
      {
        columns[k].name = table.column_name(k);
        columns[k].unit = table.column_unit(k);
        columns[k].values.reserve(table.n_rows());
        for (std::size_t i = 0; i < table.n_rows(); ++i)
          columns[k].values.push_back(table.row(i)[k]);
      }
    output.write_with(name, [&](const std::string &tmp) {
      write_series_hdf5(tmp, columns);
    });
  }



  io::Table
  read_table_hdf5(const std::string &path)
  {
    const auto  columns = read_series_hdf5(path);
    io::Table   table;
    std::size_t n = columns.empty() ? 0 : columns.front().values.size();
    for (const auto &c : columns)
      {
        if (c.components != 1 || c.values.size() != n)
          throw std::runtime_error(path + ": dataset " + c.name
                                   + " is not a column of " + std::to_string(n)
                                   + " values");
        table.add_column(c.name, c.unit);
      }
    for (std::size_t i = 0; i < n; ++i)
      {
        std::vector<double> row;
        for (const auto &c : columns)
          row.push_back(c.values[i]);
        table.add_row(row);
      }
    return table;
  }



  std::vector<SeriesDataset>
  measurement_point_series(const io::Table   &table,
                           const std::size_t  first_column,
                           const BlockSystem &system)
  {
    const auto       &points = system.measurement_points;
    const std::size_t n = table.n_rows(), p = points.size();
    if (first_column + 5 * p > table.n_columns())
      throw std::logic_error("measurement_point_series: the table has "
                             + std::to_string(table.n_columns())
                             + " columns, not 5 per point from "
                             + std::to_string(first_column));
    std::vector<SeriesDataset> sets{{"time", "s", 1, {}},
                                    {"ux", "m", p, {}},
                                    {"uy", "m", p, {}},
                                    {"sigma_x", "Pa", p, {}},
                                    {"sigma_y", "Pa", p, {}},
                                    {"tau_xy", "Pa", p, {}}};
    for (std::size_t i = 0; i < n; ++i)
      {
        const auto &row = table.row(i);
        sets[0].values.push_back(row[0]);
        for (std::size_t q = 0; q < 5; ++q)
          for (std::size_t m = 0; m < p; ++m)
            sets[1 + q].values.push_back(row[first_column + 5 * m + q]);
      }
    SeriesDataset initial{"initial_position", "m", 2, {}};
    for (const auto &m : points)
      initial.values.insert(initial.values.end(),
                            {m.initial.x() + system.origin.x(),
                             m.initial.y() + system.origin.y()});
    sets.push_back(std::move(initial));
    return sets;
  }



  Hdf5Series::Hdf5Series(const io::OutputDirectory &output, const MPI_Comm comm)
      : output(output)
      , comm(comm)
  {}



  std::string
  Hdf5Series::write(const double    time,
                    const Snapshot &blocks,
                    const Snapshot &contacts)
  {
    char name[64];
    std::snprintf(name, sizeof(name), "snapshot-%05zu.h5", entries.size());
    // Collective over several ranks; on one, only if the folder is ours.
    int ranks = 1;
    if (comm != MPI_COMM_SELF)
      MPI_Comm_size(comm, &ranks);
    std::pair<SnapshotLayout, SnapshotLayout> layouts{layout_of(blocks),
                                                      layout_of(contacts)};
    output.own(name);
    if (ranks > 1 || output.writes())
      layouts
        = write_snapshot_hdf5(output.file(name), time, blocks, contacts, comm);
    entries.emplace_back(time, name);
    add_grids(time, name, blocks, contacts, layouts);
    write_indices();
    return name;
  }



  void
  Hdf5Series::restore(const std::vector<std::pair<double, std::string>> &files)
  {
    entries.clear();
    block_grids.clear();
    contact_grids.clear();
    for (const auto &[time, name] : files)
      {
        if (name.size() < 3 || name.compare(name.size() - 3, 3, ".h5") != 0)
          throw std::runtime_error(
            "the checkpoint's snapshot series is not HDF5 (" + name
            + "): resume with the Snapshot format it was written with");
        const std::string path     = output.file(name);
        const Snapshot    blocks   = read_snapshot_hdf5(path, "blocks");
        const Snapshot    contacts = read_snapshot_hdf5(path, "contacts");
        add_grids(time,
                  name,
                  blocks,
                  contacts,
                  {layout_of(blocks), layout_of(contacts)});
        entries.emplace_back(time, name);
      }
    write_indices();
  }



  void
  Hdf5Series::add_grids(
    const double                                     time,
    const std::string                               &file,
    const Snapshot                                  &blocks,
    const Snapshot                                  &contacts,
    const std::pair<SnapshotLayout, SnapshotLayout> &layouts)
  {
    block_grids.push_back(grid(time, file, "blocks", blocks, layouts.first));
    contact_grids.push_back(
      grid(time, file, "contacts", contacts, layouts.second));
  }



  void
  Hdf5Series::write_indices() const
  {
    output.write("blocks.xdmf", index("blocks", block_grids));
    output.write("contacts.xdmf", index("contacts", contact_grids));
  }
} // namespace rockdda::dda
