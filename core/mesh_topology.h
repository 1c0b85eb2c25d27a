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
// on the boundary or used by more than two triangles. Sides are grouped by
// their smaller vertex in compressed rows (linear in the triangles); ids far
// sparser than the triangles are grouped by a sort instead.
inline std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<std::array<int, 3>>& tris) {
  std::vector<std::array<int, 3>> nbr(tris.size(), {-1, -1, -1});
  int nv = 0;
  for (const auto& t : tris) nv = std::max({nv, t[0] + 1, t[1] + 1, t[2] + 1});
  struct Half {
    uint64_t key;
    int t, k;
  };
  std::vector<Half> half(tris.size() * 3);
  // Pairs the sides of equal key in half[lo, hi), sorted by key: exactly two.
  auto pair_up = [&](size_t lo, size_t hi) {
    for (size_t i = lo; i < hi;) {
      size_t j = i + 1;
      while (j < hi && half[j].key == half[i].key) ++j;
      if (j == i + 2) {
        nbr[half[i].t][half[i].k] = half[i + 1].t;
        nbr[half[i + 1].t][half[i + 1].k] = half[i].t;
      }
      i = j;
    }
  };
  auto by_key = [](const Half& x, const Half& y) { return x.key < y.key; };
  if (static_cast<size_t>(nv) > 4 * tris.size() + 16) {
    for (int t = 0; t < static_cast<int>(tris.size()); ++t)
      for (int k = 0; k < 3; ++k) half[3 * t + k] = {edge_key(tris[t][k], tris[t][(k + 1) % 3]), t, k};
    std::sort(half.begin(), half.end(), by_key);
    pair_up(0, half.size());
    return nbr;
  }
  std::vector<int> start(nv + 1, 0);
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      half[fill[std::min(a, b)]++] = {edge_key(a, b), t, k};
    }
  for (int v = 0; v < nv; ++v) {
    if (start[v + 1] - start[v] < 2) continue;
    std::sort(half.begin() + start[v], half.begin() + start[v + 1], by_key);
    pair_up(start[v], start[v + 1]);
  }
  return nbr;
}

}  // namespace sizemesh
