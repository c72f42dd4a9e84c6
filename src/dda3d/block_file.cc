/**
 * @file
 * Reader and writer of the 3D DDA block file
 * (doc/block-file-format-dda3d.md).
 */
#include <rockdda/dda/block_file.h>
#include <rockdda/dda3d/block_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/keyword_reader.h>
#include <rockdda/io/text.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace rockdda::dda3d
{
  BlockSystem
  read_block_file(const std::string &file_name)
  {
    return parse_block_text(io::read_text_file(file_name, "block file"),
                            file_name);
  }



  BlockSystem
  parse_block_text(const std::string &text, const std::string &name)
  {
    BlockSystem        system;
    std::map<int, int> materials, blocks, joints;
    std::vector<int>   material_line;
    // Per block: the line of its 'block' line and of each face.
    std::vector<int>              block_line, block_material_id, block_joint_id;
    std::vector<std::vector<int>> face_line;
    struct Pending
    {
      int                 line, block;
      std::string         kind;
      std::vector<double> values;
    };
    std::vector<Pending> pending;

    io::KeywordReader reader(text, "block file '" + name + "'");
    while (reader.next())
      {
        const std::string              &keyword = reader.keyword;
        const std::vector<std::string> &words   = reader.words;
        const std::string              &where   = reader.where;
        const int                       line_no = reader.line;
        auto expect = [&](std::size_t n, const char *form) {
          if (words.size() != n)
            throw InputError(where + "expected '" + form + "'");
        };
        auto current_block = [&]() -> Block & {
          if (system.blocks.empty())
            throw InputError(where + "'" + keyword
                             + "' before the first 'block' line");
          return system.blocks.back();
        };
        if (keyword == "material")
          {
            expect(4, "material ID DENSITY E NU");
            const int id = reader.integer(0);
            if (materials.count(id))
              throw InputError(where + "material " + std::to_string(id)
                               + " is defined twice");
            Material m;
            m.id                  = id;
            m.density             = reader.number(1);
            m.young               = reader.number(2);
            m.poisson             = reader.number(3);
            const std::string mat = where + "material " + std::to_string(id);
            if (!(m.young > 0.))
              throw InputError(mat + ": Young's modulus " + words[2]
                               + " Pa; valid: > 0");
            if (!(m.poisson >= 0. && m.poisson < 0.5))
              throw InputError(mat + ": Poisson's ratio " + words[3]
                               + "; valid: 0 <= nu < 0.5");
            materials[id] = int(system.materials.size());
            material_line.push_back(line_no);
            system.materials.push_back(m);
          }
        else if (keyword == "joint")
          {
            const auto [id, j] = dda::joint_line(reader);
            if (joints.count(id))
              throw InputError(where + "joint " + std::to_string(id)
                               + " is defined twice");
            joints[id] = int(system.joints.size());
            system.joints.push_back(j);
          }
        else if (keyword == "block")
          {
            if (words.size() != 2 && words.size() != 3)
              throw InputError(where + "expected 'block ID MATERIAL [JOINT]'");
            Block b;
            b.id = reader.integer(0);
            if (blocks.count(b.id))
              throw InputError(where + "block " + std::to_string(b.id)
                               + " is defined twice");
            blocks[b.id] = int(system.blocks.size());
            block_material_id.push_back(reader.integer(1));
            block_joint_id.push_back(words.size() == 3 ? reader.integer(2)
                                                       : -1);
            block_line.push_back(line_no);
            face_line.emplace_back();
            system.blocks.push_back(b);
          }
        else if (keyword == "vertex")
          {
            expect(3, "vertex x y z");
            Block &b = current_block();
            b.polyhedron.vertices.emplace_back(reader.number(0),
                                               reader.number(1),
                                               reader.number(2));
          }
        else if (keyword == "face")
          {
            if (words.size() < 3)
              throw InputError(where
                               + "expected 'face V0 V1 V2 ...' (at least 3 "
                                 "vertex indices, counted from 0 in the "
                                 "block)");
            Block           &b = current_block();
            std::vector<int> face;
            for (std::size_t k = 0; k < words.size(); ++k)
              face.push_back(reader.integer(k));
            b.polyhedron.faces.push_back(face);
            face_line.back().push_back(line_no);
          }
        else if (const std::size_t n = dda::point_line_words(keyword, 3))
          {
            auto [id, values] = reader.id_and_numbers(n);
            pending.push_back({line_no, id, keyword, std::move(values)});
          }
        else
          throw InputError(where + "unknown keyword '" + keyword
                           + "'; valid: material, joint, block, vertex, "
                             "face, fixed, fixed-block, load, measure, "
                             "velocity");
      }
    if (system.blocks.empty())
      throw InputError("block file '" + name + "': no blocks");
    if (system.joints.empty())
      {
        // The default joint: phi = 30 deg, no cohesion, tension or
        // stiffness (as in 2D), id 0.
        system.joints.push_back(dda::JointMaterial());
        joints[0] = 0;
      }
    for (std::size_t b = 0; b < system.blocks.size(); ++b)
      {
        Block            &block = system.blocks[b];
        const std::string where = "block file '" + name + "', line ";
        const std::string head  = where + std::to_string(block_line[b])
                                 + ": block " + std::to_string(block.id);
        const auto m = materials.find(block_material_id[b]);
        if (m == materials.end())
          throw InputError(head + ": material "
                           + std::to_string(block_material_id[b])
                           + " is not defined");
        block.material = m->second;
        if (block_joint_id[b] >= 0 || system.joints.size() > 1)
          {
            const int  jid = block_joint_id[b] >= 0 ? block_joint_id[b] : 0;
            const auto j   = joints.find(jid);
            if (j == joints.end())
              throw InputError(head + ": joint " + std::to_string(jid)
                               + " is not defined"
                               + (block_joint_id[b] < 0
                                    ? " (give the block's joint: 'block ID "
                                      "MATERIAL JOINT')"
                                    : ""));
            block.joint = j->second;
          }
        const double rho = system.materials[m->second].density;
        if (!(rho > 0.))
          throw InputError(
            where + std::to_string(material_line[m->second]) + ": material "
            + std::to_string(m->first) + " of block " + std::to_string(block.id)
            + ": density " + std::to_string(rho) + " kg/m^3; valid: > 0");
        const auto defect = polyhedron_defect(block.polyhedron);
        if (defect)
          {
            if (defect.face >= 0)
              throw InputError(where + std::to_string(face_line[b][defect.face])
                               + ": block " + std::to_string(block.id)
                               + ", face " + std::to_string(defect.face) + ": "
                               + defect.message);
            throw InputError(head + ": " + defect.message);
          }
      }
    for (const auto &p : pending)
      {
        const std::string where
          = "block file '" + name + "', line " + std::to_string(p.line) + ": ";
        const auto b = blocks.find(p.block);
        if (b == blocks.end())
          throw InputError(where + "block " + std::to_string(p.block)
                           + " is not defined");
        const int    idx   = b->second;
        const Block &block = system.blocks[idx];
        const auto  &v     = p.values;
        auto         at    = [&](const std::size_t k) {
          const Point x(v[k], v[k + 1], v[k + 2]);
          if (!block.polyhedron.contains(x))
            throw InputError(
              where + "'" + p.kind + "': the point (" + std::to_string(x.x())
              + ", " + std::to_string(x.y()) + ", " + std::to_string(x.z())
              + ") is outside block " + std::to_string(block.id));
          return x;
        };
        if (p.kind == "fixed")
          system.fixed_points.push_back({idx, at(0), Point::Zero()});
        else if (p.kind == "fixed-block")
          for (const auto &x : block.polyhedron.vertices)
            system.fixed_points.push_back({idx, x, Point::Zero()});
        else if (p.kind == "load")
          system.load_points.push_back({idx, at(0), Point(v[3], v[4], v[5])});
        else if (p.kind == "measure")
          system.measurement_points.push_back({idx, at(0), Point::Zero()});
        else
          {
            Vector12 &vel = system.blocks[idx].velocity;
            vel.head<3>() = Point(v[0], v[1], v[2]);
            // Angular velocity (wx, wy, wz) -> (r1, r2, r3) = (wz, wx, wy).
            vel[3] = v[5];
            vel[4] = v[3];
            vel[5] = v[4];
          }
      }
    validate_and_prepare(system);
    return system;
  }



  std::string
  block_text(const BlockSystem &system)
  {
    std::ostringstream out;
    out.precision(17);
    out << "# 3D DDA block file (doc/block-file-format-dda3d.md)\n";
    for (std::size_t m = 0; m < system.materials.size(); ++m)
      {
        const auto &mat = system.materials[m];
        out << "material " << (mat.id >= 0 ? mat.id : int(m)) << ' '
            << mat.density << ' ' << mat.young << ' ' << mat.poisson << '\n';
      }
    for (std::size_t j = 0; j < system.joints.size(); ++j)
      {
        const auto &jm = system.joints[j];
        out << "joint " << j << ' ' << jm.friction_deg << ' ' << jm.cohesion
            << ' ' << jm.tensile << ' ' << jm.normal_stiffness << ' '
            << jm.shear_stiffness << '\n';
      }
    for (const auto &b : system.blocks)
      {
        const auto &mat = system.materials[b.material];
        out << "block " << b.id << ' ' << (mat.id >= 0 ? mat.id : b.material);
        if (!system.joints.empty())
          out << ' ' << b.joint;
        out << '\n';
        for (const auto &v : b.polyhedron.vertices)
          out << "vertex " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
        for (const auto &f : b.polyhedron.faces)
          {
            out << "face";
            for (const int k : f)
              out << ' ' << k;
            out << '\n';
          }
      }
    for (const auto &f : system.fixed_points)
      out << "fixed " << system.blocks[f.block].id << ' ' << f.point.x() << ' '
          << f.point.y() << ' ' << f.point.z() << '\n';
    for (const auto &l : system.load_points)
      out << "load " << system.blocks[l.block].id << ' ' << l.point.x() << ' '
          << l.point.y() << ' ' << l.point.z() << ' ' << l.force.x() << ' '
          << l.force.y() << ' ' << l.force.z() << '\n';
    for (const auto &m : system.measurement_points)
      out << "measure " << system.blocks[m.block].id << ' ' << m.point.x()
          << ' ' << m.point.y() << ' ' << m.point.z() << '\n';
    return out.str();
  }
} // namespace rockdda::dda3d
