/**
 * @file
 * Reader of the DDA block file (doc/block-file-format-dda.md).
 */
#include <rockdda/dda/block_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/keyword_reader.h>
#include <rockdda/io/text.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace rockdda::dda
{
  BlockSystem
  read_block_file(const std::string &file_name)
  {
    return parse_block_text(io::read_text_file(file_name, "block file"),
                            file_name);
  }



  std::pair<int, JointMaterial>
  joint_line(const io::KeywordReader &reader)
  {
    const auto &words = reader.words;
    const char *form  = "joint ID FRICTION_DEG COHESION TENSILE "
                        "[NORMAL_STIFFNESS SHEAR_STIFFNESS]";
    if (words.size() != 4 && words.size() != 6)
      throw InputError(
        reader.where + "expected '" + form + "'"
        + (words.size() == 5 ? " (both stiffnesses or neither)" : ""));
    const int     id = reader.integer(0);
    JointMaterial j;
    j.friction_deg = reader.number(1);
    j.cohesion     = reader.number(2);
    j.tensile      = reader.number(3);
    if (words.size() == 6)
      for (const std::size_t k : {std::size_t(4), std::size_t(5)})
        {
          char        *end = nullptr;
          const double v   = std::strtod(words[k].c_str(), &end);
          if (end == words[k].c_str() || *end != '\0' || !std::isfinite(v)
              || !(v >= 0.))
            throw InputError(reader.where + "joint " + std::to_string(id) + ": "
                             + (k == 4 ? "normal" : "shear") + " stiffness '"
                             + words[k]
                             + "' Pa/m; valid: a number >= 0 (0: a rigid "
                               "joint, only the contact penalty acts)");
          (k == 4 ? j.normal_stiffness : j.shear_stiffness) = v;
        }
    return {id, j};
  }



  BlockSystem
  parse_block_text(const std::string &text, const std::string &name)
  {
    BlockSystem        system;
    std::map<int, int> materials, joints, blocks;

    struct Pending
    {
      int                 line, block;
      std::string         kind;
      std::vector<double> values;
    };
    std::vector<Pending> pending;
    std::vector<int>     block_material_id, block_joint_id, block_line;
    io::KeywordReader    reader(text, "block file '" + name + "'");
    while (reader.next())
      {
        const std::string              &keyword = reader.keyword;
        const std::vector<std::string> &words   = reader.words;
        const std::string              &where   = reader.where;
        const int                       line_no = reader.line;
        auto expect = [&](std::size_t lo, std::size_t hi, const char *form) {
          if (words.size() < lo || words.size() > hi)
            throw InputError(where + "expected '" + form + "'");
        };
        if (keyword == "material")
          {
            expect(4,
                   5,
                   "material ID DENSITY E NU [plane-stress|plane-strain]");
            const int id = reader.integer(0);
            if (materials.count(id))
              throw InputError(where + "material " + std::to_string(id)
                               + " is defined twice");
            BlockMaterial m;
            m.id      = id;
            m.density = reader.number(1);
            m.young   = reader.number(2);
            m.poisson = reader.number(3);
            if (words.size() == 5)
              {
                if (words[4] != "plane-stress" && words[4] != "plane-strain")
                  throw InputError(where + "'" + words[4]
                                   + "': valid: plane-stress, plane-strain");
                m.plane_strain = words[4] == "plane-strain";
              }
            materials[id] = static_cast<int>(system.materials.size());
            system.materials.push_back(m);
          }
        else if (keyword == "joint")
          {
            const auto [id, j] = joint_line(reader);
            if (joints.count(id))
              throw InputError(where + "joint " + std::to_string(id)
                               + " is defined twice");
            joints[id] = static_cast<int>(system.joints.size());
            system.joints.push_back(j);
          }
        else if (keyword == "block")
          {
            if (words.size() < 3 + 6 || (words.size() - 3) % 2 != 0)
              throw InputError(
                where
                + "expected 'block ID MATERIAL JOINT x1 y1 x2 y2 x3 y3 ...' "
                  "(at least 3 vertices)");
            Block b;
            b.id = reader.integer(0);
            if (blocks.count(b.id))
              throw InputError(where + "block " + std::to_string(b.id)
                               + " is defined twice");
            block_material_id.push_back(reader.integer(1));
            block_joint_id.push_back(reader.integer(2));
            block_line.push_back(line_no);
            for (std::size_t k = 3; k + 1 < words.size(); k += 2)
              b.polygon.vertices.emplace_back(reader.number(k),
                                              reader.number(k + 1));
            blocks[b.id] = static_cast<int>(system.blocks.size());
            system.blocks.push_back(b);
          }
        else if (keyword == "edge-joints")
          {
            if (words.size() < 4)
              throw InputError(where
                               + "expected 'edge-joints BLOCK J0 J1 J2 ...' "
                                 "(one joint id per edge)");
            Pending p{line_no, reader.integer(0), keyword, {}};
            for (std::size_t k = 1; k < words.size(); ++k)
              p.values.push_back(reader.integer(k));
            pending.push_back(p);
          }
        else if (const std::size_t n = dda::point_line_words(keyword, 2))
          {
            auto [id, values] = reader.id_and_numbers(n);
            pending.push_back({line_no, id, keyword, std::move(values)});
          }
        else
          throw InputError(where + "unknown keyword '" + keyword
                           + "'; valid: material, joint, block, "
                             "edge-joints, fixed, fixed-block, load, "
                             "measure, velocity");
      }
    if (system.blocks.empty())
      throw InputError("block file '" + name + "': no blocks");
    if (system.joints.empty())
      {
        system.joints.push_back(JointMaterial());
        joints[0] = 0;
      }
    for (std::size_t b = 0; b < system.blocks.size(); ++b)
      {
        const std::string where = "block file '" + name + "', line "
                                  + std::to_string(block_line[b]) + ": block "
                                  + std::to_string(system.blocks[b].id);
        auto m = materials.find(block_material_id[b]);
        if (m == materials.end())
          throw InputError(where + ": has no material (material "
                           + std::to_string(block_material_id[b])
                           + " is not defined)");
        system.blocks[b].material = m->second;
        auto j                    = joints.find(block_joint_id[b]);
        if (j == joints.end())
          throw InputError(where + ": joint material "
                           + std::to_string(block_joint_id[b])
                           + " is not defined");
        system.blocks[b].joint = j->second;
      }
    for (const auto &p : pending)
      {
        auto b = blocks.find(p.block);
        if (b == blocks.end())
          throw InputError("block file '" + name + "', line "
                           + std::to_string(p.line) + ": block "
                           + std::to_string(p.block) + " is not defined");
        const int idx = b->second;
        if (p.kind == "edge-joints")
          {
            auto &block = system.blocks[idx];
            if (p.values.size() != block.polygon.vertices.size())
              throw InputError("block file '" + name + "', line "
                               + std::to_string(p.line) + ": block "
                               + std::to_string(p.block) + " has "
                               + std::to_string(block.polygon.vertices.size())
                               + " edges but " + std::to_string(p.values.size())
                               + " edge joint ids are given");
            block.edge_joints.clear();
            for (const double id : p.values)
              {
                auto j = joints.find(static_cast<int>(id));
                if (j == joints.end())
                  throw InputError("block file '" + name + "', line "
                                   + std::to_string(p.line) + ": joint "
                                   + std::to_string(static_cast<int>(id))
                                   + " is not defined");
                block.edge_joints.push_back(j->second);
              }
          }
        else if (p.kind == "fixed")
          {
            FixedPoint f;
            f.block = idx;
            f.point = geometry::Point(p.values[0], p.values[1]);
            system.fixed_points.push_back(f);
          }
        else if (p.kind == "fixed-block")
          for (const auto &v : system.blocks[idx].polygon.vertices)
            {
              FixedPoint f;
              f.block = idx;
              f.point = v;
              system.fixed_points.push_back(f);
            }
        else if (p.kind == "load")
          {
            LoadPoint l;
            l.block = idx;
            l.point = geometry::Point(p.values[0], p.values[1]);
            l.force = geometry::Point(p.values[2], p.values[3]);
            system.load_points.push_back(l);
          }
        else if (p.kind == "measure")
          {
            MeasurementPoint m;
            m.block = idx;
            m.point = geometry::Point(p.values[0], p.values[1]);
            system.measurement_points.push_back(m);
          }
        else
          {
            auto &v = system.blocks[idx].velocity;
            v[0]    = p.values[0];
            v[1]    = p.values[1];
            v[2]    = p.values[2];
          }
      }
    return system;
  }
} // namespace rockdda::dda
