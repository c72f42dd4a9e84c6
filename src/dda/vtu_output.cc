/**
 * @file
 * VTK XML output of DDA blocks and contacts: binary (base64) DataArrays,
 * zlib-compressed when deal.II was built with zlib.
 */
#include <rockdda/dda/vtu_output.h>

#include <deal.II/base/config.h>

#ifdef DEAL_II_WITH_ZLIB
#  include <zlib.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rockdda::dda
{
  namespace
  {
    /// VTK type name of the values written.
    template <typename T>
    const char *
    vtk_type();
    template <>
    const char *
    vtk_type<double>()
    {
      return "Float64";
    }
    template <>
    const char *
    vtk_type<std::int32_t>()
    {
      return "Int32";
    }
    template <>
    const char *
    vtk_type<std::int64_t>()
    {
      return "Int64";
    }
    template <>
    const char *
    vtk_type<std::uint8_t>()
    {
      return "UInt8";
    }

    /// Append the base64 encoding (RFC 4648, with padding) of @p n bytes.
    void
    append_base64(std::string &out, const unsigned char *data, std::size_t n)
    {
      static const char digits[]
        = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      out.reserve(out.size() + 4 * ((n + 2) / 3));
      std::size_t i = 0;
      for (; i + 3 <= n; i += 3)
        {
          const std::uint32_t w = (std::uint32_t(data[i]) << 16)
                                  | (std::uint32_t(data[i + 1]) << 8)
                                  | std::uint32_t(data[i + 2]);
          out += digits[(w >> 18) & 63];
          out += digits[(w >> 12) & 63];
          out += digits[(w >> 6) & 63];
          out += digits[w & 63];
        }
      if (i < n)
        {
          const bool          two = i + 1 < n;
          const std::uint32_t w   = (std::uint32_t(data[i]) << 16)
                                  | (two ? std::uint32_t(data[i + 1]) << 8 : 0);
          out += digits[(w >> 18) & 63];
          out += digits[(w >> 12) & 63];
          out += two ? digits[(w >> 6) & 63] : '=';
          out += '=';
        }
    }

    template <typename T>
    void
    append_base64(std::string &out, const std::vector<T> &values)
    {
      append_base64(out,
                    reinterpret_cast<const unsigned char *>(values.data()),
                    values.size() * sizeof(T));
    }

    /// Whether this machine stores numbers little-endian (the files are
    /// written in the machine's byte order and say which).
    bool
    little_endian()
    {
      const std::uint16_t one = 1;
      unsigned char       first;
      std::memcpy(&first, &one, 1);
      return first == 1;
    }

    /**
     * The text of a binary DataArray holding @p n bytes at @p data, as VTK
     * reads it with header_type UInt64. Compressed: the header (number of
     * blocks, block size, size of the last partial block or 0, compressed
     * size of each block) and the concatenated zlib streams of the blocks,
     * each base64-encoded on its own. Uncompressed: the byte count and the
     * bytes, base64-encoded together.
     */
    std::string
    encode(const unsigned char *data, const std::size_t n)
    {
      std::string out;
#ifdef DEAL_II_WITH_ZLIB
      const std::size_t          block    = std::size_t(1) << 16;
      const std::size_t          n_blocks = (n + block - 1) / block;
      std::vector<std::uint64_t> header   = {n_blocks, block, n % block};
      std::vector<unsigned char> compressed;
      for (std::size_t b = 0; b < n_blocks; ++b)
        {
          const std::size_t size  = std::min(block, n - b * block);
          uLongf            bound = compressBound(size);
          const std::size_t at    = compressed.size();
          compressed.resize(at + bound);
          if (compress2(compressed.data() + at,
                        &bound,
                        data + b * block,
                        size,
                        Z_BEST_SPEED)
              != Z_OK)
            throw std::runtime_error("VTU output: zlib compression failed");
          compressed.resize(at + bound);
          header.push_back(bound);
        }
      append_base64(out, header);
      append_base64(out, compressed);
#else
      std::vector<unsigned char> bytes(sizeof(std::uint64_t) + n);
      const std::uint64_t        size = n;
      std::memcpy(bytes.data(), &size, sizeof(size));
      std::memcpy(bytes.data() + sizeof(size), data, n);
      append_base64(out, bytes);
#endif
      return out;
    }

    /// A binary DataArray of @p values (@p components per tuple).
    template <typename T>
    void
    data_array(std::ostringstream             &s,
               const std::string              &name,
               const int                       components,
               const std::vector<T>           &values,
               const std::vector<std::string> &component_names = {})
    {
      s << "<DataArray type=\"" << vtk_type<T>() << "\"";
      if (!name.empty())
        s << " Name=\"" << name << "\"";
      s << " NumberOfComponents=\"" << components << "\"";
      for (std::size_t c = 0; c < component_names.size(); ++c)
        s << " ComponentName" << c << "=\"" << component_names[c] << "\"";
      s << " format=\"binary\">\n"
        << encode(reinterpret_cast<const unsigned char *>(values.data()),
                  values.size() * sizeof(T))
        << "\n</DataArray>\n";
    }

    /// The XML declaration, @p description as a comment, and the opening
    /// of the piece.
    void
    header(std::ostringstream &s,
           const std::string  &description,
           std::size_t         n_points,
           std::size_t         n_cells)
    {
      s << "<?xml version=\"1.0\"?>\n<!--\n"
        << description << "-->\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\""
        << (little_endian() ? "LittleEndian" : "BigEndian")
        << "\" header_type=\"UInt64\"";
#ifdef DEAL_II_WITH_ZLIB
      s << " compressor=\"vtkZLibDataCompressor\"";
#endif
      s << ">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
        << n_cells << "\">\n";
    }

    /// Points (x, y, 0) and cells of one VTK type with @p offsets.
    void
    geometry(std::ostringstream              &s,
             const std::vector<double>       &xyz,
             const std::vector<std::int64_t> &offsets,
             const std::uint8_t               cell_type)
    {
      s << "<Points>\n";
      data_array(s, "", 3, xyz);
      s << "</Points>\n<Cells>\n";
      std::vector<std::int64_t> connectivity(xyz.size() / 3);
      for (std::size_t k = 0; k < connectivity.size(); ++k)
        connectivity[k] = static_cast<std::int64_t>(k);
      data_array(s, "connectivity", 1, connectivity);
      data_array(s, "offsets", 1, offsets);
      data_array(s,
                 "types",
                 1,
                 std::vector<std::uint8_t>(offsets.size(), cell_type));
      s << "</Cells>\n";
    }

    void
    footer(std::ostringstream &s)
    {
      s << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    }

    /// Cell data of 3 components (x, y, 0) from 2D values.
    std::vector<double>
    planar_vectors(const std::vector<geometry::Point> &v)
    {
      std::vector<double> out;
      out.reserve(3 * v.size());
      for (const auto &p : v)
        out.insert(out.end(), {p.x(), p.y(), 0.});
      return out;
    }
  } // namespace



  std::string
  blocks_vtu(const DdaSystem &dda)
  {
    const auto                  &scene  = dda.system();
    const auto                  &blocks = scene.blocks;
    const std::size_t            n      = blocks.size();
    const geometry::Point        o      = scene.origin;
    std::vector<double>          xyz;
    std::vector<std::int64_t>    offsets;
    std::vector<std::int32_t>    id(n), material(n);
    std::vector<geometry::Point> displacement(n), velocity(n);
    std::vector<double>          rotation(n), stress;
    stress.reserve(6 * n);
    for (std::size_t i = 0; i < n; ++i)
      {
        const Block &b = blocks[i];
        // Global coordinates (origin + local).
        for (const auto &v : b.polygon.vertices)
          xyz.insert(xyz.end(), {o.x() + v.x(), o.y() + v.y(), 0.});
        offsets.push_back(static_cast<std::int64_t>(xyz.size() / 3));
        id[i] = b.id;
        const int user_material
          = b.material >= 0
                && b.material < static_cast<int>(scene.materials.size())
                && scene.materials[b.material].id >= 0
              ? scene.materials[b.material].id
              : b.material;
        material[i]     = user_material;
        displacement[i] = dda.centroid_displacement(static_cast<int>(i));
        velocity[i]     = geometry::Point(b.velocity[0], b.velocity[1]);
        rotation[i]     = b.rotation;
        stress.insert(stress.end(),
                      {b.stress[0], b.stress[1], 0., b.stress[2], 0., 0.});
      }
    std::ostringstream s;
    header(s,
           "rockdda dda blocks (one polygon cell per block; points in m).\n"
           "Cell data: block_id (block file id), material (block file "
           "material id),\n"
           "displacement (m) and velocity (m/s) of the centroid, rotation "
           "(rad),\n"
           "stress (Pa, tension positive; symmetric tensor XX YY ZZ XY YZ "
           "XZ,\n"
           "the out-of-plane components written as 0).\n",
           xyz.size() / 3,
           n);
    geometry(s, xyz, offsets, 7); // VTK_POLYGON
    s << "<CellData Scalars=\"material\" Vectors=\"displacement\" "
         "Tensors=\"stress\">\n";
    data_array(s, "block_id", 1, id);
    data_array(s, "material", 1, material);
    data_array(s, "displacement", 3, planar_vectors(displacement));
    data_array(s, "velocity", 3, planar_vectors(velocity));
    data_array(s, "rotation", 1, rotation);
    data_array(s, "stress", 6, stress, {"XX", "YY", "ZZ", "XY", "YZ", "XZ"});
    s << "</CellData>\n";
    footer(s);
    return s.str();
  }



  std::string
  contacts_vtu(const DdaSystem &dda)
  {
    const auto                  &contacts = dda.contacts();
    const auto                  &scene    = dda.system();
    const auto                  &blocks   = scene.blocks;
    const geometry::Point        o        = scene.origin;
    const std::size_t            n        = contacts.size();
    std::vector<double>          xyz, gap(n), slip(n), fn(n), fs(n);
    std::vector<std::int64_t>    offsets(n);
    std::vector<std::int32_t>    state(n), vertex_block(n), edge_block(n);
    std::vector<geometry::Point> normal(n);
    for (std::size_t c = 0; c < n; ++c)
      {
        // The contact's vertex and edge in the current geometry (the
        // contact records hold the detection at the start of the step).
        const auto           &g  = contacts[c].geometry;
        const auto           &vi = blocks[g.block_i].polygon.vertices;
        const auto           &vj = blocks[g.block_j].polygon.vertices;
        const geometry::Point P  = vi[g.vertex];
        const geometry::Point Q0 = vj[g.edge];
        const geometry::Point E  = vj[(g.edge + 1) % vj.size()] - Q0;
        const double          l  = E.norm();
        const geometry::Point t  = E / l;
        const geometry::Point nn(t.y(), -t.x()); // out of block j
        const double          xi = std::clamp(t.dot(P - Q0) / l, 0., 1.);
        const geometry::Point P0 = Q0 + xi * E;
        xyz.insert(xyz.end(),
                   {o.x() + P.x(),
                    o.y() + P.y(),
                    0.,
                    o.x() + P0.x(),
                    o.y() + P0.y(),
                    0.});
        offsets[c]      = static_cast<std::int64_t>(2 * (c + 1));
        state[c]        = static_cast<std::int32_t>(contacts[c].state);
        vertex_block[c] = blocks[g.block_i].id;
        edge_block[c]   = blocks[g.block_j].id;
        gap[c]          = nn.dot(P - Q0);
        slip[c]         = contacts[c].state == ContactState::open
                            ? 0.
                            : t.dot(P - (Q0 + contacts[c].xi_ref * E));
        fn[c]           = contacts[c].normal_force;
        fs[c]           = contacts[c].shear_force;
        normal[c]       = nn;
      }
    std::ostringstream s;
    header(s,
           "rockdda dda contacts (one line cell per contact, from the "
           "vertex to its\n"
           "projection on the edge; points in m). Cell data:\n"
           "state: 0 open, 1 sliding, 2 locked;\n"
           "vertex_block, edge_block: block file ids of the block whose "
           "vertex\n"
           "touches and of the block whose edge is touched;\n"
           "normal_gap (m, negative = penetration);\n"
           "shear_slip (m, along the edge from the shear reference: "
           "locked, the\n"
           "elastic shear displacement; sliding, the slip of the last "
           "step; open, 0);\n"
           "normal_force (N/m, compression positive), "
           "shear_force (N/m), normal (outward unit normal of the edge).\n",
           2 * n,
           n);
    geometry(s, xyz, offsets, 3); // VTK_LINE
    s << "<CellData Scalars=\"state\" Vectors=\"normal\">\n";
    data_array(s, "state", 1, state);
    data_array(s, "vertex_block", 1, vertex_block);
    data_array(s, "edge_block", 1, edge_block);
    data_array(s, "normal_gap", 1, gap);
    data_array(s, "shear_slip", 1, slip);
    data_array(s, "normal_force", 1, fn);
    data_array(s, "shear_force", 1, fs);
    data_array(s, "normal", 3, planar_vectors(normal));
    s << "</CellData>\n";
    footer(s);
    return s.str();
  }



  std::string
  pvd(const std::vector<std::pair<double, std::string>> &entries)
  {
    std::ostringstream s;
    s << std::setprecision(12)
      << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
         "version=\"0.1\">\n<Collection>\n";
    for (const auto &[t, f] : entries)
      s << "<DataSet timestep=\"" << t << "\" file=\"" << f << "\"/>\n";
    s << "</Collection>\n</VTKFile>\n";
    return s.str();
  }
} // namespace rockdda::dda
