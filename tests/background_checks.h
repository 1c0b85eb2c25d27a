// Watertightness of a background mesh, shared by the background and
// refinement tests.
#pragma once

#include <map>
#include <set>

#include "background/background_mesh.h"
#include "core/geometry.h"

namespace sizemesh::test {

// Background edges not used by exactly two triangles: a curve edge by two in
// all, an edge inside a face by two of that face. Edges at a pole (the B-rep
// point a degenerated curve collapses to) are left out: a face that reaches
// its pole from two sides of its parameter space fans around it twice (the
// manta's wing tips), which the size map does not mind. An edge inside a
// face is counted per face: two faces that each join the same two boundary
// vertices by a chord (a corner point and a node of a curve they share)
// hold one vertex pair each, which is still a closed mesh.
inline int open_background_edges(const Geometry& g, const BackgroundMesh& bg) {
  std::set<int> poles;
  for (int c = 1; c <= g.num_curves(); ++c)
    if (g.curve_degenerated(c)) poles.insert({g.curve_start_point(c), g.curve_end_point(c)});
  auto at_pole = [&](int v) { return bg.dim[v] == 0 && poles.count(bg.entity[v]) > 0; };
  const std::vector<int> valence = bg.edge_valence();
  std::map<std::pair<int, int>, int> in_face;  // (inner edge, face) -> triangles
  for (size_t t = 0; t < bg.tris.size(); ++t)
    for (int e : bg.tri_edges[t])
      if (bg.edge_curve[e] == 0) ++in_face[{e, bg.tri_face[t]}];
  int open = 0;
  for (size_t e = 0; e < valence.size(); ++e) {
    if (at_pole(bg.edges[e][0]) || at_pole(bg.edges[e][1])) continue;
    if (bg.edge_curve[e] != 0) {
      open += valence[e] != 2;
      continue;
    }
    for (auto it = in_face.lower_bound({static_cast<int>(e), 0});
         it != in_face.end() && it->first.first == static_cast<int>(e); ++it)
      open += it->second != 2;
  }
  return open;
}
}  // namespace sizemesh::test
