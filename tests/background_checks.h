// Watertightness of a background mesh, shared by the background and
// refinement tests.
#pragma once

#include <set>

#include "geometry/background_mesh.h"
#include "geometry/geometry.h"

namespace sizemesh::test {

// Background edges not used by exactly two triangles. Edges at a pole (the
// B-rep point a degenerated curve collapses to) are left out: a face that
// reaches its pole from two sides of its parameter space fans around it twice
// (the manta's wing tips), which the size map does not mind.
inline int open_background_edges(const Geometry& g, const BackgroundMesh& bg) {
  std::set<int> poles;
  for (int c = 1; c <= g.num_curves(); ++c)
    if (g.curve_degenerated(c)) poles.insert({g.curve_start_point(c), g.curve_end_point(c)});
  auto at_pole = [&](int v) { return bg.dim[v] == 0 && poles.count(bg.entity[v]) > 0; };
  const std::vector<int> valence = bg.edge_valence();
  int open = 0;
  for (size_t e = 0; e < valence.size(); ++e)
    if (valence[e] != 2 && !at_pole(bg.edges[e][0]) && !at_pole(bg.edges[e][1])) ++open;
  return open;
}

}  // namespace sizemesh::test
