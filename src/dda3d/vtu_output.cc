/**
 * @file
 * ASCII VTK XML output of polyhedral blocks; contacts through the 2D
 * engine's snapshot writer.
 */
#include <rockdda/dda/vtu_output.h>
#include <rockdda/dda3d/vtu_output.h>

#include <cstdint>
#include <sstream>

namespace rockdda::dda3d
{
  namespace
  {
    /// The cell data both writers give a block: its ids, centroid
    /// displacement (m), velocity (m/s), stress (Pa) and volume (m^3).
    struct BlockFields
    {
      std::int32_t id = 0, material = 0;
      Point        displacement = Point::Zero();
      Point        velocity     = Point::Zero();
      Vector6      stress       = Vector6::Zero();
      double       volume       = 0.;
    };

    BlockFields
    block_fields(const BlockSystem &system, const Block &b)
    {
      const auto  m    = b.polyhedron.moments();
      const int   user = system.materials[b.material].id;
      BlockFields out;
      out.id           = b.id;
      out.material     = user >= 0 ? user : b.material;
      out.displacement = m.centroid - b.initial_centroid;
      out.velocity     = b.velocity.head<3>();
      out.stress       = b.stress;
      out.volume       = m.volume;
      return out;
    }
  } // namespace



  std::string
  blocks_vtu(const BlockSystem &system, const Point &origin)
  {
    std::size_t n_points = 0;
    for (const auto &b : system.blocks)
      n_points += b.polyhedron.vertices.size();
    std::ostringstream out;
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n"
        << "<!-- rockdda 3D DDA blocks: one VTK_POLYHEDRON (42) per block; "
           "cell data block_id, material, displacement (m), velocity "
           "(m/s), stress (Pa, tension positive; XX YY ZZ XY YZ XZ), "
           "volume (m^3) -->\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        << "<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
        << system.blocks.size() << "\">\n"
        << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    for (const auto &b : system.blocks)
      for (const auto &v : b.polyhedron.vertices)
        {
          const Point x = v + origin;
          out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
        }
    out << "</DataArray>\n</Points>\n<Cells>\n";
    // connectivity / offsets: each cell's own points; faces: per cell the
    // number of faces, then per face the number of points and their ids.
    std::ostringstream connectivity, offsets, types, faces, faceoffsets;
    std::int64_t       first = 0, face_end = 0;
    for (const auto &b : system.blocks)
      {
        const auto &p = b.polyhedron;
        for (std::size_t k = 0; k < p.vertices.size(); ++k)
          connectivity << first + std::int64_t(k) << ' ';
        offsets << first + std::int64_t(p.vertices.size()) << ' ';
        types << "42 ";
        faces << p.faces.size() << ' ';
        face_end += 1;
        for (const auto &f : p.faces)
          {
            faces << f.size();
            for (const int k : f)
              faces << ' ' << first + k;
            faces << '\n';
            face_end += 1 + std::int64_t(f.size());
          }
        faceoffsets << face_end << ' ';
        first += std::int64_t(p.vertices.size());
      }
    auto array = [&](const char *type, const char *name, const std::string &s) {
      out << "<DataArray type=\"" << type << "\" Name=\"" << name
          << "\" format=\"ascii\">\n"
          << s << "\n</DataArray>\n";
    };
    array("Int64", "connectivity", connectivity.str());
    array("Int64", "offsets", offsets.str());
    array("UInt8", "types", types.str());
    array("Int64", "faces", faces.str());
    array("Int64", "faceoffsets", faceoffsets.str());
    out << "</Cells>\n<CellData>\n";
    std::ostringstream id, material, disp, vel, stress, volume;
    for (auto *s : {&id, &material, &disp, &vel, &stress, &volume})
      s->precision(17);
    for (const auto &b : system.blocks)
      {
        const BlockFields c = block_fields(system, b);
        id << c.id << ' ';
        material << c.material << ' ';
        const Point &d = c.displacement;
        disp << d.x() << ' ' << d.y() << ' ' << d.z() << '\n';
        vel << c.velocity.x() << ' ' << c.velocity.y() << ' ' << c.velocity.z()
            << '\n';
        for (int k = 0; k < 6; ++k)
          stress << c.stress[k] << (k == 5 ? '\n' : ' ');
        volume << c.volume << ' ';
      }
    array("Int32", "block_id", id.str());
    array("Int32", "material", material.str());
    out << "<DataArray type=\"Float64\" Name=\"displacement\" "
           "NumberOfComponents=\"3\" format=\"ascii\">\n"
        << disp.str() << "</DataArray>\n"
        << "<DataArray type=\"Float64\" Name=\"velocity\" "
           "NumberOfComponents=\"3\" format=\"ascii\">\n"
        << vel.str() << "</DataArray>\n"
        << "<DataArray type=\"Float64\" Name=\"stress\" "
           "NumberOfComponents=\"6\" format=\"ascii\">\n"
        << stress.str() << "</DataArray>\n";
    array("Float64", "volume", volume.str());
    out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    return out.str();
  }


  dda::Snapshot
  blocks_snapshot(const BlockSystem &system, const Point &origin)
  {
    dda::Snapshot             out;
    std::vector<std::int32_t> id, material;
    std::vector<double>       disp, vel, stress, volume;
    std::int64_t              end = 0;
    for (const auto &b : system.blocks)
      {
        const BlockFields c = block_fields(system, b);
        for (const auto &f : b.polyhedron.faces)
          {
            for (const int k : f)
              {
                const Point x = b.polyhedron.vertices[k] + origin;
                out.xyz.insert(out.xyz.end(), {x.x(), x.y(), x.z()});
              }
            end += static_cast<std::int64_t>(f.size());
            out.offsets.push_back(end);
            id.push_back(c.id);
            material.push_back(c.material);
            disp.insert(disp.end(),
                        {c.displacement.x(),
                         c.displacement.y(),
                         c.displacement.z()});
            vel.insert(vel.end(),
                       {c.velocity.x(), c.velocity.y(), c.velocity.z()});
            stress.insert(stress.end(), c.stress.data(), c.stress.data() + 6);
            volume.push_back(c.volume);
          }
      }
    out.description
      = "rockdda 3D DDA blocks: one polygon cell per face of every block "
        "(counter-clockwise seen from outside; points in m).\n"
        "Cell data, the face's block's: block_id, material; displacement "
        "(m, centroid);\n"
        "velocity (m/s); stress (Pa, tension positive; XX YY ZZ XY YZ XZ); "
        "volume (m^3).\n";
    out.fields.push_back(dda::integer_field("block_id", std::move(id)));
    out.fields.push_back(dda::integer_field("material", std::move(material)));
    out.fields.push_back(dda::real_field("displacement", 3, std::move(disp)));
    out.fields.push_back(dda::real_field("velocity", 3, std::move(vel)));
    out.fields.push_back(dda::real_field("stress", 6, std::move(stress)));
    out.fields.push_back(dda::real_field("volume", 1, std::move(volume)));
    out.scalars = "block_id";
    out.vectors = "displacement";
    out.tensors = "stress";
    return out;
  }



  dda::Snapshot
  contacts_snapshot(const Engine &engine)
  {
    const auto               &contacts = engine.contacts();
    const auto               &blocks   = engine.scene().blocks;
    const Point              &o        = engine.origin();
    const std::size_t         n        = contacts.size();
    dda::Snapshot             out;
    std::vector<std::int32_t> state(n), type(n), bi(n), bj(n);
    std::vector<double>       gap(n), fn(n), area(n), fs, normal;
    out.lines = true;
    out.offsets.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      {
        const auto &c = contacts[k];
        const auto &g = c.geometry;
        const Point p = g.p + o, q = g.q + o;
        out.xyz.insert(out.xyz.end(),
                       {p.x(), p.y(), p.z(), q.x(), q.y(), q.z()});
        out.offsets[k] = static_cast<std::int64_t>(2 * (k + 1));
        state[k]       = static_cast<std::int32_t>(c.state);
        type[k]        = g.type == ContactType::vertex_face ? 0 : 1;
        bi[k]          = blocks[g.i].id;
        bj[k]          = blocks[g.j].id;
        gap[k]         = g.gap;
        fn[k]          = c.normal_force;
        area[k]        = c.area;
        fs.insert(fs.end(),
                  {c.shear_force.x(), c.shear_force.y(), c.shear_force.z()});
        normal.insert(normal.end(), {g.normal.x(), g.normal.y(), g.normal.z()});
      }
    out.description
      = "rockdda 3D DDA contacts (one line cell per contact, from its point "
        "on block i\n"
        "to its point on block j at detection, the start of the last "
        "step; points in m).\n"
        "Cell data: state: 0 open, 1 sliding, 2 locked; type: 0 "
        "vertex-face, 1 edge-edge;\n"
        "block_i, block_j: block ids (i owns the vertex or the first "
        "edge);\n"
        "normal_gap (m, at detection, negative = penetration); "
        "normal_force (N,\n"
        "compression positive); shear_force (N, on block i); normal "
        "(unit, out of block j);\n"
        "area (m^2, the contact's share of the touching faces' overlap).\n";
    out.fields.push_back(dda::integer_field("state", std::move(state)));
    out.fields.push_back(dda::integer_field("type", std::move(type)));
    out.fields.push_back(dda::integer_field("block_i", std::move(bi)));
    out.fields.push_back(dda::integer_field("block_j", std::move(bj)));
    out.fields.push_back(dda::real_field("normal_gap", 1, std::move(gap)));
    out.fields.push_back(dda::real_field("normal_force", 1, std::move(fn)));
    out.fields.push_back(dda::real_field("shear_force", 3, std::move(fs)));
    out.fields.push_back(dda::real_field("normal", 3, std::move(normal)));
    out.fields.push_back(dda::real_field("area", 1, std::move(area)));
    out.scalars = "state";
    out.vectors = "normal";
    return out;
  }



  std::string
  contacts_vtu(const Engine &engine)
  {
    return dda::vtu(contacts_snapshot(engine));
  }
} // namespace rockdda::dda3d
