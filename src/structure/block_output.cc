#include <rockdda/io/error.h>
#include <rockdda/io/text.h>
#include <rockdda/structure/block_output.h>
#include <rockdda/structure/statistics.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace rockdda::structure
{
  std::string
  block_file_text(const BlockSet &blocks)
  {
    std::ostringstream out;
    out << std::setprecision(17);
    out << "rockdda-blocks 1\n"
        << "# Blocks cut by rockdda (doc/block-file-format.md). Units: m.\n"
        << "# Edge i of a block runs from its vertex i to vertex i+1 and "
           "carries the tag on vertex i's line.\n"
        << "vertices " << blocks.vertices.size() << "\n";
    for (std::size_t i = 0; i < blocks.vertices.size(); ++i)
      out << i << " " << blocks.vertices[i].x() << " " << blocks.vertices[i].y()
          << "\n";
    out << "blocks " << blocks.blocks.size() << "\n";
    for (std::size_t b = 0; b < blocks.blocks.size(); ++b)
      {
        const Block &blk = blocks.blocks[b];
        out << "block " << b << " " << blk.vertex_ids.size() << "\n";
        for (std::size_t i = 0; i < blk.vertex_ids.size(); ++i)
          out << blk.vertex_ids[i] << " " << to_string(blk.edge_tags[i].kind)
              << " " << blk.edge_tags[i].set << "\n";
      }
    return out.str();
  }



  namespace
  {
    /// Lines without comments and blanks, with their numbers.
    class Lines
    {
    public:
      Lines(const std::string &text, const std::string &name)
          : name(name)
      {
        std::istringstream in(text);
        std::string        line;
        unsigned int       number = 0;
        while (std::getline(in, line))
          {
            ++number;
            const auto hash = line.find('#');
            if (hash != std::string::npos)
              line.erase(hash);
            if (line.find_first_not_of(" \t\r") == std::string::npos)
              continue;
            lines.emplace_back(number, line);
          }
      }

      std::istringstream
      next()
      {
        if (pos >= lines.size())
          fail("unexpected end of file");
        current = lines[pos].first;
        return std::istringstream(lines[pos++].second);
      }

      [[noreturn]] void
      fail(const std::string &what) const
      {
        throw InputError(name + ":" + std::to_string(current) + ": " + what);
      }

    private:
      std::string                                       name;
      std::vector<std::pair<unsigned int, std::string>> lines;
      std::size_t                                       pos     = 0;
      unsigned int                                      current = 0;
    };

    EdgeKind
    kind_from_string(const std::string &s, const Lines &lines)
    {
      for (const EdgeKind k : {EdgeKind::boundary,
                               EdgeKind::bedding,
                               EdgeKind::joint,
                               EdgeKind::excavation,
                               EdgeKind::split})
        if (to_string(k) == s)
          return k;
      lines.fail("unknown edge kind '" + s
                 + "' (boundary, bedding, joint, excavation or split)");
    }
  } // namespace



  BlockSet
  parse_block_file(const std::string &text, const std::string &name)
  {
    Lines       lines(text, name);
    BlockSet    set;
    std::string word;
    long        count = -1, version = 0;
    {
      auto in = lines.next();
      if (!(in >> word >> version) || word != "rockdda-blocks" || version != 1)
        lines.fail("first line must be 'rockdda-blocks 1'");
    }
    {
      auto in = lines.next();
      if (!(in >> word >> count) || word != "vertices" || count < 0)
        lines.fail("expected 'vertices N' with N >= 0");
    }
    for (long i = 0; i < count; ++i)
      {
        auto   in = lines.next();
        long   id;
        double x, y;
        if (!(in >> id >> x >> y) || id != i || !std::isfinite(x)
            || !std::isfinite(y))
          lines.fail("expected vertex line '" + std::to_string(i)
                     + " x y' with finite x, y (m)");
        set.vertices.emplace_back(x, y);
      }
    {
      auto in = lines.next();
      if (!(in >> word >> count) || word != "blocks" || count < 0)
        lines.fail("expected 'blocks M' with M >= 0");
    }
    for (long b = 0; b < count; ++b)
      {
        long id, n;
        {
          auto in = lines.next();
          if (!(in >> word >> id >> n) || word != "block" || id != b || n < 3)
            lines.fail("expected 'block " + std::to_string(b)
                       + " n' with n >= 3 vertices");
        }
        Block blk;
        for (long i = 0; i < n; ++i)
          {
            auto        in = lines.next();
            long        v, s;
            std::string kind;
            if (!(in >> v >> kind >> s) || v < 0
                || v >= long(set.vertices.size()) || s < 0)
              lines.fail("expected 'vertex kind set' with 0 <= vertex < "
                         + std::to_string(set.vertices.size())
                         + " and set >= 0");
            blk.vertex_ids.push_back(v);
            blk.polygon.vertices.push_back(set.vertices[v]);
            blk.edge_tags.push_back({kind_from_string(kind, lines), int(s)});
          }
        if (!(blk.polygon.signed_area() > 0.))
          lines.fail("block " + std::to_string(b)
                     + " has a non-positive area (vertices must be counter-"
                       "clockwise)");
        set.blocks.push_back(std::move(blk));
      }
    return set;
  }



  namespace
  {
    /// DDA joint id of an edge tag: 1 boundary and excavation, 2 bedding,
    /// 3 split (fictitious cut, glued), 10 + k joint set k.
    int
    dda_joint_id(const EdgeTag &tag)
    {
      switch (tag.kind)
        {
          case EdgeKind::bedding:
            return 2;
          case EdgeKind::split:
            return 3;
          case EdgeKind::joint:
            return 10 + tag.set;
          default:
            return 1;
        }
    }
  } // namespace



  std::string
  dda_block_file_text(const BlockSet                 &blocks,
                      const std::vector<std::size_t> &fixed)
  {
    std::ostringstream out;
    out << std::setprecision(17);
    out << "# Blocks cut by rockdda, in the DDA scene format "
           "(doc/block-file-format-dda.md).\n"
        << "# One joint material per edge tag: 1 boundary/excavation, 2 "
           "bedding,\n# 3 split (a fictitious cut of a face with a hole: "
           "glued), 10+k joint set k.\n# Edit the material and joint lines "
           "(friction deg, cohesion Pa, tensile Pa).\n"
        << "material 1 2300 15.3e9 0.21 plane-strain\n";
    std::set<int> ids;
    for (const auto &b : blocks.blocks)
      for (const auto &t : b.edge_tags)
        ids.insert(dda_joint_id(t));
    ids.insert(1);
    for (const int id : ids)
      out << "joint " << id << (id == 3 ? " 45 1e9 1e9" : " 30 0 0") << "\n";
    for (std::size_t b = 0; b < blocks.blocks.size(); ++b)
      {
        out << "block " << b << " 1 1 ";
        for (const Point &p : blocks.blocks[b].polygon.vertices)
          out << " " << p.x() << " " << p.y();
        out << "\nedge-joints " << b;
        for (const auto &t : blocks.blocks[b].edge_tags)
          out << " " << dda_joint_id(t);
        out << "\n";
      }
    for (const std::size_t b : fixed)
      out << "fixed-block " << b << "\n";
    return out.str();
  }



  std::vector<std::size_t>
  boundary_blocks(const BlockSet &blocks,
                  const bool      bottom,
                  const bool      sides,
                  const Polygon  &region)
  {
    const double             c45 = std::sqrt(0.5);
    std::vector<std::size_t> list;
    for (std::size_t b = 0; b < blocks.blocks.size(); ++b)
      {
        const Block &blk  = blocks.blocks[b];
        const auto  &v    = blk.polygon.vertices;
        const double sign = blk.polygon.signed_area() > 0. ? 1. : -1.;
        bool         hit
          = !region.vertices.empty() && region.contains(blk.polygon.centroid());
        for (std::size_t k = 0; k < v.size() && !hit; ++k)
          {
            if (blk.edge_tags[k].kind != EdgeKind::boundary)
              continue;
            const Point  d = v[(k + 1) % v.size()] - v[k];
            const double l = d.norm();
            if (!(l > 0.))
              continue;
            // Outward normal of a counter-clockwise boundary: (dy, -dx).
            const double nx = sign * d.y() / l, ny = -sign * d.x() / l;
            hit = (bottom && ny < -c45) || (sides && std::abs(nx) > c45);
          }
        if (hit)
          list.push_back(b);
      }
    return list;
  }



  BlockSet
  read_block_file(const std::string &file_name)
  {
    return parse_block_file(io::read_text_file(file_name, "block file"),
                            file_name);
  }



  namespace
  {
    void
    vtu_points(std::ostream &out, const BlockSet &blocks)
    {
      out << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
             "format=\"ascii\">\n";
      for (const Point &p : blocks.vertices)
        out << p.x() << " " << p.y() << " 0\n";
      out << "</DataArray></Points>\n";
    }
  } // namespace



  std::string
  blocks_vtu(const BlockSet &blocks, const double bedding_dip_deg)
  {
    std::ostringstream out;
    out << std::setprecision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
           "version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << blocks.vertices.size()
        << "\" NumberOfCells=\"" << blocks.blocks.size() << "\">\n";
    vtu_points(out, blocks);
    out << "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
           "format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      {
        for (const std::size_t v : b.vertex_ids)
          out << v << " ";
        out << "\n";
      }
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    std::size_t offset = 0;
    for (const Block &b : blocks.blocks)
      out << (offset += b.vertex_ids.size()) << "\n";
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (std::size_t i = 0; i < blocks.blocks.size(); ++i)
      out << "7\n"; // VTK_POLYGON
    out << "</DataArray>\n</Cells>\n<CellData Scalars=\"block\">\n"
        << "<DataArray type=\"Int64\" Name=\"block\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < blocks.blocks.size(); ++i)
      out << i << "\n";
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"area_m2\" "
           "format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      out << b.polygon.area() << "\n";
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"width_m\" "
           "format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      out << block_width(b, bedding_dip_deg) << "\n";
    out << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n"
           "</VTKFile>\n";
    return out.str();
  }



  std::string
  edges_vtu(const BlockSet &blocks)
  {
    std::size_t n = 0;
    for (const Block &b : blocks.blocks)
      n += b.vertex_ids.size();
    std::ostringstream out;
    out << std::setprecision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
           "version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << blocks.vertices.size()
        << "\" NumberOfCells=\"" << n << "\">\n";
    vtu_points(out, blocks);
    out << "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
           "format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      for (std::size_t i = 0; i < b.vertex_ids.size(); ++i)
        out << b.vertex_ids[i] << " "
            << b.vertex_ids[(i + 1) % b.vertex_ids.size()] << "\n";
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    for (std::size_t i = 1; i <= n; ++i)
      out << 2 * i << "\n";
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i)
      out << "3\n"; // VTK_LINE
    out << "</DataArray>\n</Cells>\n<CellData Scalars=\"kind\">\n"
        << "<DataArray type=\"Int32\" Name=\"kind\" format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      for (const EdgeTag &t : b.edge_tags)
        out << int(t.kind) << "\n";
    out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"set\" "
           "format=\"ascii\">\n";
    for (const Block &b : blocks.blocks)
      for (const EdgeTag &t : b.edge_tags)
        out << t.set << "\n";
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"block\" "
           "format=\"ascii\">\n";
    for (std::size_t k = 0; k < blocks.blocks.size(); ++k)
      for (std::size_t i = 0; i < blocks.blocks[k].vertex_ids.size(); ++i)
        out << k << "\n";
    out << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n"
           "</VTKFile>\n";
    return out.str();
  }
} // namespace rockdda::structure
