/**
 * @file
 * HDF5 snapshots and XDMF indices of a DDA run (the HDF5 C library that
 * deal.II links).
 */
#include <rockdda/dda/hdf5_output.h>

#include <cstdio>
#include <hdf5.h>
#include <iomanip>
#include <sstream>
#include <stdexcept>

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

    template <typename T>
    void
    write_dataset(const hid_t                 group,
                  const std::string          &name,
                  const hid_t                 type,
                  const std::vector<T>       &values,
                  const std::vector<hsize_t> &dims,
                  const std::string          &where)
    {
      const Handle space(H5Screate_simple(static_cast<int>(dims.size()),
                                          dims.data(),
                                          nullptr),
                         H5Sclose,
                         "create a dataspace for " + where + name);
      const Handle set(H5Dcreate2(group,
                                  name.c_str(),
                                  type,
                                  space,
                                  H5P_DEFAULT,
                                  H5P_DEFAULT,
                                  H5P_DEFAULT),
                       H5Dclose,
                       "create dataset " + where + name);
      if (!values.empty())
        check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
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

    void
    write_group(const hid_t        file,
                const std::string &name,
                const Snapshot    &s,
                const std::string &path)
    {
      const std::string where = path + ":/" + name + "/";
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
      write_dataset(
        group, "points", H5T_NATIVE_DOUBLE, s.xyz, {s.n_points(), 3}, where);
      write_dataset(group, "offsets", H5T_NATIVE_INT64, s.offsets, {n}, where);
      std::vector<std::int64_t> topology;
      if (s.lines)
        {
          topology.resize(s.n_points());
          for (std::size_t k = 0; k < topology.size(); ++k)
            topology[k] = static_cast<std::int64_t>(k);
          write_dataset(
            group, "topology", H5T_NATIVE_INT64, topology, {n, 2}, where);
        }
      else
        {
          topology.reserve(2 * n + s.n_points());
          std::int64_t begin = 0;
          for (const auto end : s.offsets)
            {
              topology.push_back(3); // XDMF polygon
              topology.push_back(end - begin);
              for (std::int64_t k = begin; k < end; ++k)
                topology.push_back(k);
              begin = end;
            }
          write_dataset(group,
                        "topology",
                        H5T_NATIVE_INT64,
                        topology,
                        {topology.size()},
                        where);
        }
      for (const auto &f : s.fields)
        {
          std::vector<hsize_t> dims = {n};
          if (f.components > 1)
            dims.push_back(static_cast<hsize_t>(f.components));
          if (f.integer.empty())
            write_dataset(
              group, f.name, H5T_NATIVE_DOUBLE, f.real, dims, where);
          else
            write_dataset(
              group, f.name, H5T_NATIVE_INT32, f.integer, dims, where);
        }
    }

    /// The XDMF <Grid> of one group of one snapshot.
    std::string
    grid(const double       time,
         const std::string &file,
         const std::string &group,
         const Snapshot    &s)
    {
      const std::string  h5 = file + ":/" + group + "/";
      std::ostringstream x;
      x << std::setprecision(12);
      const std::size_t n = s.n_cells();
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
          << "\">\n     <DataItem Dimensions=\"" << 2 * n + s.n_points()
          << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5
          << "topology</DataItem>\n    </Topology>\n";
      x << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\""
        << s.n_points()
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
        << "points</DataItem>\n    </Geometry>\n";
      for (const auto &f : s.fields)
        {
          const char *kind = f.components == 1   ? "Scalar"
                             : f.components == 3 ? "Vector"
                                                 : "Matrix";
          x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\""
            << kind << "\" Center=\"Cell\">\n     <DataItem Dimensions=\"" << n;
          if (f.components > 1)
            x << " " << f.components;
          x << "\" NumberType=\"" << (f.integer.empty() ? "Float" : "Int")
            << "\" Precision=\"" << (f.integer.empty() ? 8 : 4)
            << "\" Format=\"HDF\">" << h5 << f.name
            << "</DataItem>\n    </Attribute>\n";
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



  void
  write_snapshot_hdf5(const std::string &path,
                      const double       time,
                      const Snapshot    &blocks,
                      const Snapshot    &contacts)
  {
    const Handle file(
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
      H5Fclose,
      "create " + path);
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
    write_group(file, "blocks", blocks, path);
    write_group(file, "contacts", contacts, path);
    check(H5Fflush(file, H5F_SCOPE_LOCAL), "flush " + path);
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
    H5G_info_t info;
    check(H5Gget_info(group, &info), "list " + where);
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
        const std::string n = name;
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



  Hdf5Series::Hdf5Series(const io::OutputDirectory &output)
      : output(output)
  {}



  std::string
  Hdf5Series::write(const double    time,
                    const Snapshot &blocks,
                    const Snapshot &contacts)
  {
    char name[64];
    std::snprintf(name, sizeof(name), "snapshot-%05zu.h5", entries.size());
    output.write_with(name, [&](const std::string &path) {
      write_snapshot_hdf5(path, time, blocks, contacts);
    });
    entries.emplace_back(time, name);
    add_grids(time, name, blocks, contacts);
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
        const std::string path = output.file(name);
        add_grids(time,
                  name,
                  read_snapshot_hdf5(path, "blocks"),
                  read_snapshot_hdf5(path, "contacts"));
        entries.emplace_back(time, name);
      }
    write_indices();
  }



  void
  Hdf5Series::add_grids(const double       time,
                        const std::string &file,
                        const Snapshot    &blocks,
                        const Snapshot    &contacts)
  {
    block_grids.push_back(grid(time, file, "blocks", blocks));
    contact_grids.push_back(grid(time, file, "contacts", contacts));
  }



  void
  Hdf5Series::write_indices() const
  {
    output.write("blocks.xdmf", index("blocks", block_grids));
    output.write("contacts.xdmf", index("contacts", contact_grids));
  }
} // namespace rockdda::dda
