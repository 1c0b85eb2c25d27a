// Triangles around every vertex of a triangle list, in compressed rows: the
// one adjacency the size smoothing (background mesh) and the face optimiser
// (face meshes) walk.
#pragma once

#include <array>
#include <vector>

namespace sizemesh {

// Those of vertex v are ids[start[v] .. start[v+1]), in increasing order.
inline void vertex_triangles(int num_vertices, const std::vector<std::array<int, 3>>& tris, std::vector<int>& start,
                             std::vector<int>& ids) {
  start.assign(num_vertices + 1, 0);
  for (const auto& t : tris)
    for (int v : t) ++start[v + 1];
  for (int v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  ids.resize(start[num_vertices]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int v : tris[t]) ids[fill[v]++] = t;
}

}  // namespace sizemesh
