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
  } // namespace



  std::string
  vtu(const Snapshot &snapshot)
  {
    std::ostringstream s;
    header(s, snapshot.description, snapshot.n_points(), snapshot.n_cells());
    geometry(s,
             snapshot.xyz,
             snapshot.offsets,
             snapshot.lines ? 3 : 7); // VTK_LINE, VTK_POLYGON
    s << "<CellData Scalars=\"" << snapshot.scalars << "\"";
    if (!snapshot.vectors.empty())
      s << " Vectors=\"" << snapshot.vectors << "\"";
    if (!snapshot.tensors.empty())
      s << " Tensors=\"" << snapshot.tensors << "\"";
    s << ">\n";
    for (const auto &f : snapshot.fields)
      if (f.integer.empty())
        data_array(s, f.name, f.components, f.real, f.component_names);
      else
        data_array(s, f.name, f.components, f.integer, f.component_names);
    s << "</CellData>\n";
    footer(s);
    return s.str();
  }



  std::string
  blocks_vtu(const DdaSystem &dda)
  {
    return vtu(blocks_snapshot(dda));
  }



  std::string
  contacts_vtu(const DdaSystem &dda)
  {
    return vtu(contacts_snapshot(dda));
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
