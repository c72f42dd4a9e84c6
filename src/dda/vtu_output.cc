/**
 * @file
 * VTK XML output of DDA blocks and contacts.
 */
#include <rockdda/dda/vtu_output.h>

#include <iomanip>
#include <sstream>

namespace rockdda::dda
{
  namespace
  {
    void
    header(std::ostringstream &s, std::size_t n_points, std::size_t n_cells)
    {
      s << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
        << n_cells << "\">\n";
    }

    void
    footer(std::ostringstream &s)
    {
      s << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    }

    template <typename F>
    void
    cell_array(std::ostringstream &s,
               const char         *name,
               int                 components,
               std::size_t         n,
               F                 &&value)
    {
      s << "<DataArray type=\"Float64\" Name=\"" << name
        << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
      for (std::size_t i = 0; i < n; ++i)
        {
          for (int c = 0; c < components; ++c)
            s << value(i, c) << ' ';
          s << '\n';
        }
      s << "</DataArray>\n";
    }
  } // namespace



  std::string
  blocks_vtu(const DdaSystem &dda)
  {
    const auto &blocks   = dda.system().blocks;
    std::size_t n_points = 0;
    for (const auto &b : blocks)
      n_points += b.polygon.vertices.size();
    std::ostringstream s;
    s << std::setprecision(10);
    header(s, n_points, blocks.size());
    s << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
    // Global coordinates (origin + local), to 0.1 um at UTM magnitudes.
    const geometry::Point o = dda.system().origin;
    s << std::setprecision(15);
    for (const auto &b : blocks)
      for (const auto &v : b.polygon.vertices)
        s << o.x() + v.x() << ' ' << o.y() + v.y() << " 0\n";
    s << std::setprecision(10);
    s << "</DataArray>\n</Points>\n<Cells>\n"
      << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    std::size_t k = 0;
    for (const auto &b : blocks)
      {
        for (std::size_t v = 0; v < b.polygon.vertices.size(); ++v)
          s << k++ << ' ';
        s << '\n';
      }
    s << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
         "format=\"ascii\">\n";
    k = 0;
    for (const auto &b : blocks)
      s << (k += b.polygon.vertices.size()) << '\n';
    s << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
         "format=\"ascii\">\n";
    for (std::size_t b = 0; b < blocks.size(); ++b)
      s << "7\n";
    s << "</DataArray>\n</Cells>\n<CellData>\n";
    const std::size_t n = blocks.size();
    cell_array(s, "block_id", 1, n, [&](std::size_t i, int) {
      return static_cast<double>(blocks[i].id);
    });
    cell_array(s, "material", 1, n, [&](std::size_t i, int) {
      return static_cast<double>(blocks[i].material);
    });
    std::vector<geometry::Point> disp(n);
    for (std::size_t i = 0; i < n; ++i)
      disp[i] = dda.centroid_displacement(static_cast<int>(i));
    cell_array(s, "displacement", 3, n, [&](std::size_t i, int c) {
      return c < 2 ? disp[i][c] : 0.;
    });
    cell_array(s, "velocity", 3, n, [&](std::size_t i, int c) {
      return c < 2 ? blocks[i].velocity[c] : 0.;
    });
    cell_array(s, "rotation", 1, n, [&](std::size_t i, int) {
      return blocks[i].rotation;
    });
    cell_array(s, "stress", 3, n, [&](std::size_t i, int c) {
      return blocks[i].stress[c];
    });
    s << "</CellData>\n";
    footer(s);
    return s.str();
  }



  std::string
  contacts_vtu(const DdaSystem &dda)
  {
    const auto        &contacts = dda.contacts();
    const auto        &blocks   = dda.system().blocks;
    std::ostringstream s;
    s << std::setprecision(10);
    header(s, 2 * contacts.size(), contacts.size());
    s << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
    for (const auto &c : contacts)
      {
        const auto &g  = c.geometry;
        const auto &vi = blocks[g.block_i].polygon.vertices;
        const auto &vj = blocks[g.block_j].polygon.vertices;
        const auto  P  = vi[g.vertex];
        const auto  Q0 = vj[g.edge];
        const auto  Q1 = vj[(g.edge + 1) % vj.size()];
        const auto  P0 = Q0 + g.xi * (Q1 - Q0);
        const auto &o  = dda.system().origin;
        s << std::setprecision(15) << o.x() + P.x() << ' ' << o.y() + P.y()
          << " 0\n"
          << o.x() + P0.x() << ' ' << o.y() + P0.y() << " 0\n"
          << std::setprecision(10);
      }
    s << "</DataArray>\n</Points>\n<Cells>\n"
      << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t c = 0; c < contacts.size(); ++c)
      s << 2 * c << ' ' << 2 * c + 1 << '\n';
    s << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
         "format=\"ascii\">\n";
    for (std::size_t c = 0; c < contacts.size(); ++c)
      s << 2 * (c + 1) << '\n';
    s << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
         "format=\"ascii\">\n";
    for (std::size_t c = 0; c < contacts.size(); ++c)
      s << "3\n";
    s << "</DataArray>\n</Cells>\n<CellData>\n";
    const std::size_t n = contacts.size();
    cell_array(s, "state", 1, n, [&](std::size_t i, int) {
      return static_cast<double>(static_cast<int>(contacts[i].state));
    });
    cell_array(s, "normal_force", 1, n, [&](std::size_t i, int) {
      return contacts[i].normal_force;
    });
    cell_array(s, "shear_force", 1, n, [&](std::size_t i, int) {
      return contacts[i].shear_force;
    });
    cell_array(s, "normal", 3, n, [&](std::size_t i, int c) {
      return c < 2 ? contacts[i].geometry.normal[c] : 0.;
    });
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
