#include "io/mesh_output.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "io/cgns_writer.h"
#include "io/vtu_writer.h"

namespace sizemesh {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Gmsh 4.1: nodes are listed by the first face that uses them; elements by face.
void write_msh(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write '" + path + "'");
  std::map<int, std::vector<int>> face_tris;
  for (size_t t = 0; t < m.tris.size(); ++t) face_tris[m.tri_face[t]].push_back(static_cast<int>(t));
  std::vector<int> node_face(m.xyz.size(), 0);
  for (const auto& [f, ts] : face_tris)
    for (int t : ts)
      for (int n : m.tris[t])
        if (!node_face[n]) node_face[n] = f;
  std::map<int, std::vector<int>> face_nodes;
  for (size_t n = 0; n < m.xyz.size(); ++n)
    if (node_face[n]) face_nodes[node_face[n]].push_back(static_cast<int>(n));
  size_t used_nodes = 0;
  for (const auto& [f, ns] : face_nodes) used_nodes += ns.size();

  out.precision(17);
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  std::map<int, int> groups;  // marker -> entities in it
  for (const auto& [f, ts] : face_tris) ++groups[labels.marker_of(f)];
  out << "$PhysicalNames\n" << groups.size() << "\n";
  for (const auto& [s, n] : groups) out << "2 " << s << " \"" << labels.markers.at(s).name << "\"\n";
  out << "$EndPhysicalNames\n";
  out << "$Entities\n0 0 " << face_tris.size() << " 0\n";
  for (const auto& [f, ts] : face_tris) {
    Eigen::AlignedBox3d box;
    for (int t : ts)
      for (int n : m.tris[t]) box.extend(m.xyz[n]);
    out << f << " " << box.min().x() << " " << box.min().y() << " " << box.min().z() << " " << box.max().x() << " "
        << box.max().y() << " " << box.max().z() << " 1 " << labels.marker_of(f) << " 0\n";
  }
  out << "$EndEntities\n";
  out << "$Nodes\n" << face_nodes.size() << " " << used_nodes << " 1 " << m.xyz.size() << "\n";
  for (const auto& [f, ns] : face_nodes) {
    out << "2 " << f << " 0 " << ns.size() << "\n";
    for (int n : ns) out << n + 1 << "\n";
    for (int n : ns) out << m.xyz[n].x() << " " << m.xyz[n].y() << " " << m.xyz[n].z() << "\n";
  }
  out << "$EndNodes\n";
  out << "$Elements\n" << face_tris.size() << " " << m.tris.size() << " 1 " << m.tris.size() << "\n";
  for (const auto& [f, ts] : face_tris) {
    out << "2 " << f << " 2 " << ts.size() << "\n";
    for (int t : ts) out << t + 1 << " " << m.tris[t][0] + 1 << " " << m.tris[t][1] + 1 << " " << m.tris[t][2] + 1 << "\n";
  }
  out << "$EndElements\n";
  if (!out) throw Error("cannot write '" + path + "'");
}

void write_stl(const std::string& path, const SurfaceMesh& m) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error("cannot write '" + path + "'");
  char header[80] = "sizemesh surface mesh";
  out.write(header, 80);
  const uint32_t n = static_cast<uint32_t>(m.tris.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.tris) {
    const Vec3 a = m.xyz[t[0]], b = m.xyz[t[1]], c = m.xyz[t[2]];
    Vec3 nrm = (b - a).cross(c - a);
    if (nrm.norm() > 0) nrm.normalize();
    float rec[12];
    const Vec3* v[4] = {&nrm, &a, &b, &c};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) rec[3 * i + k] = static_cast<float>((*v[i])[k]);
    out.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
  if (!out) throw Error("cannot write '" + path + "'");
}

// Medit (Mmg and many adaptation loops): triangles carry their marker as reference.
void write_medit(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write '" + path + "'");
  out.precision(17);
  out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << m.xyz.size() << "\n";
  for (const Vec3& p : m.xyz) out << p.x() << " " << p.y() << " " << p.z() << " 0\n";
  out << "Triangles\n" << m.tris.size() << "\n";
  for (size_t t = 0; t < m.tris.size(); ++t)
    out << m.tris[t][0] + 1 << " " << m.tris[t][1] + 1 << " " << m.tris[t][2] + 1 << " "
        << labels.marker_of(m.tri_face[t]) << "\n";
  out << "End\n";
  if (!out) throw Error("cannot write '" + path + "'");
}

// TetGen's surface mesh (.smesh): facets with their marker as boundary
// marker, and a hole inside each body the far field surrounds.
void write_smesh(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write '" + path + "'");
  out.precision(17);
  out << "# sizemesh surface mesh: nodes, facets with boundary markers, holes, regions\n";
  out << m.xyz.size() << " 3 0 0\n";
  for (size_t i = 0; i < m.xyz.size(); ++i) out << i + 1 << " " << m.xyz[i].x() << " " << m.xyz[i].y() << " " << m.xyz[i].z() << "\n";
  out << m.tris.size() << " 1\n";
  for (size_t t = 0; t < m.tris.size(); ++t)
    out << "3 " << m.tris[t][0] + 1 << " " << m.tris[t][1] + 1 << " " << m.tris[t][2] + 1 << " "
        << labels.marker_of(m.tri_face[t]) << "\n";
  out << labels.holes.size() << "\n";
  for (size_t h = 0; h < labels.holes.size(); ++h)
    out << h + 1 << " " << labels.holes[h].x() << " " << labels.holes[h].y() << " " << labels.holes[h].z() << "\n";
  out << "0\n";
  if (!out) throw Error("cannot write '" + path + "'");
}

}  // namespace

void check_mesh_format(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != ".vtu" && ext != ".msh" && ext != ".stl" && ext != ".cgns" && ext != ".mesh" && ext != ".smesh")
    throw Error("unknown mesh format '" + ext + "' for '" + path + "' (use .vtu, .msh, .stl, .cgns, .mesh or .smesh)");
}

void write_mesh(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels, const MeshQuality& q,
                const std::vector<double>& target_size, const std::vector<double>& limited_by) {
  const std::string ext = extension(path);
  if (ext == ".msh") return write_msh(path, m, labels);
  if (ext == ".cgns") return write_cgns(path, m, labels);
  if (ext == ".mesh") return write_medit(path, m, labels);
  if (ext == ".smesh") return write_smesh(path, m, labels);
  if (ext == ".stl") return write_stl(path, m);
  std::vector<double> dim(m.node_dim.begin(), m.node_dim.end()), entity(m.node_entity.begin(), m.node_entity.end());
  std::vector<double> source_ids(m.tri_face.size());
  std::vector<double> composite_ids(m.tri_face.size());
  for (size_t t = 0; t < m.tri_face.size(); ++t) {
    source_ids[t] = labels.marker_of(m.tri_face[t]);
    composite_ids[t] = labels.composite_of(m.tri_face[t]);
  }
  std::vector<Field> point = {{"target_size", target_size}, {"classification_dim", dim}, {"classification_id", entity}};
  if (limited_by.size() == m.xyz.size()) point.push_back({"limited_by", limited_by});
  write_vtu(path, m.xyz, m.tris, point,
            {{"face_id", std::vector<double>(m.tri_face.begin(), m.tri_face.end())},
             {"source_face_id", source_ids},
             {"composite_id", composite_ids},
             {"min_angle", q.min_angle},
             {"sliver", std::vector<double>(q.sliver.begin(), q.sliver.end())}});
}

}  // namespace sizemesh
