// Adjacency of triangle lists, written once and used by the background mesh,
// the size smoothing, the face optimiser, the junction repair and the quality
// checks: edge keys, the triangles around each vertex, and each triangle's
// neighbour across each side.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace sizemesh {

// Key of the undirected edge (a, b) of non-negative ids, for hash maps and sorts of edges.
inline uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
}

// The triangles around every vertex, in compressed rows: those of vertex v
// are ids[start[v] .. start[v+1]), in increasing order.
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

// Each triangle's neighbour across its side (k, k+1), -1 where the side is
// on the boundary or used by more than two triangles.
inline std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<std::array<int, 3>>& tris) {
  struct Half {
    uint64_t key;
    int t, k;
  };
  std::vector<Half> half;
  half.reserve(tris.size() * 3);
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) half.push_back({edge_key(tris[t][k], tris[t][(k + 1) % 3]), t, k});
  std::sort(half.begin(), half.end(), [](const Half& x, const Half& y) {
    return x.key != y.key ? x.key < y.key : x.t < y.t;
  });
  std::vector<std::array<int, 3>> nbr(tris.size(), {-1, -1, -1});
  for (size_t i = 0; i + 1 < half.size(); ++i)
    if (half[i].key == half[i + 1].key && (i + 2 >= half.size() || half[i + 2].key != half[i].key) &&
        (i == 0 || half[i - 1].key != half[i].key)) {
      nbr[half[i].t][half[i].k] = half[i + 1].t;
      nbr[half[i + 1].t][half[i + 1].k] = half[i].t;
    }
  return nbr;
}

}  // namespace sizemesh
