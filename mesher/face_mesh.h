// A face's own mesh in its uv domain, before it joins the global mesh.
//
// Nodes carry uv, the surface sample there, and the id of the shared node on a
// B-rep point or curve (global, -1 for nodes inside the face). A pole (a
// degenerate curve) appears as several nodes distinct in uv with one global id;
// triangles on a pole are kept here (valid in uv) and dropped at assembly.
// Triangles run counter-clockwise in uv: along the surface's natural normal.
#pragma once

#include <array>
#include <vector>

#include "mesher/face_surface.h"

namespace sizemesh {

struct FaceMesh {
  int face = 0;
  std::vector<Vec2> uv;
  std::vector<SurfaceSample> s;
  std::vector<int> global;
  std::vector<char> pole;
  // Where a boundary node lies in the assembled mesh: the shared curve node's
  // xyz, which may lie off S(uv) by the CAD's edge tolerance. Read through
  // position() only: an inner node's entry is a placeholder (it lies at s.p).
  std::vector<Vec3> shared_xyz;
  std::vector<std::vector<int>> loops;  // boundary, domain on the left; loops[0] outer
  std::vector<std::array<int, 3>> tris;

  int add_node(const Vec2& p, const SurfaceSample& sample, int global_id, bool is_pole = false) {
    uv.push_back(p);
    s.push_back(sample);
    global.push_back(global_id);
    pole.push_back(is_pole);
    shared_xyz.push_back(sample.p);
    return static_cast<int>(uv.size()) - 1;
  }
  int num_nodes() const { return static_cast<int>(uv.size()); }
  // Removes the nodes marked in `removed` (used by no triangle) and renumbers
  // the others, in the triangles and loops too, keeping their order.
  void drop_nodes(const std::vector<char>& removed) {
    std::vector<int> id(uv.size(), -1);
    int n = 0;
    for (int i = 0; i < num_nodes(); ++i) {
      if (removed[i]) continue;
      id[i] = n;
      uv[n] = uv[i];
      s[n] = s[i];
      global[n] = global[i];
      pole[n] = pole[i];
      shared_xyz[n] = shared_xyz[i];
      ++n;
    }
    uv.resize(n);
    s.resize(n);
    global.resize(n);
    pole.resize(n);
    shared_xyz.resize(n);
    for (auto& loop : loops)
      for (int& v : loop) v = id[v];
    for (auto& t : tris)
      for (int& v : t) v = id[v];
  }
  bool boundary(int i) const { return global[i] >= 0; }
  // Node i's position in the assembled mesh.
  const Vec3& position(int i) const { return global[i] >= 0 ? shared_xyz[i] : s[i].p; }
  // Two corners on the same pole: zero area in space, dropped at assembly.
  bool pole_triangle(const std::array<int, 3>& t) const {
    for (int k = 0; k < 3; ++k)
      if (global[t[k]] >= 0 && global[t[k]] == global[t[(k + 1) % 3]]) return true;
    return false;
  }
};

}  // namespace sizemesh
