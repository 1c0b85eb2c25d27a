// The junction read as chains from corner to corner (Chain, Topology), each sampled again to the size map.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::cut_faces_detail {

// A triangle's corners in face f's uv, shifted by whole periods into the
// period that holds its centroid: a node on the seam takes the side of the
// triangle it is a corner of.
std::array<Vec2, 3> canonical_uv(const Geometry& g, int f, std::array<Vec2, 3> u);

// One junction polyline between two corners, and its new inner nodes.
struct Chain {
  std::vector<int> nodes;  // first to last; first == last when it closes on itself
  int fa = 0, fb = 0;      // the faces on either side
  bool usable = false;     // two faces, the same all along, with the nodes' uv on both
  std::vector<Vec3> x;     // new inner nodes: position, uv on fa and fb, node id
  std::vector<Vec2> uva, uvb;
  std::vector<int> id;
  std::vector<double> size;  // the size map at `nodes`: the finer of its two faces
};

// The mesh's edges, nodes and junction, read once.
struct Topology {
  std::unordered_map<uint64_t, std::vector<int>> edge_tris;
  std::vector<std::vector<int>> node_faces;
  std::unordered_map<uint64_t, Vec2> uv_at;  // (node, face) -> uv in a triangle of that face
  std::vector<std::vector<int>> junction_next;

  std::vector<char> on_seam;

  Topology(const SurfaceMesh& s, const Geometry& g, const std::vector<std::array<int, 2>>& junction);
  static uint64_t key(int n, int f) { return (uint64_t(uint32_t(n)) << 32) | uint32_t(f); }
  const Vec2* uv(int n, int f) const {
    const auto it = uv_at.find(key(n, f));
    return it == uv_at.end() ? nullptr : &it->second;
  }
  // Where a junction ends or branches, meets a CAD curve or a third face, or
  // crosses a seam (a face's loop passes it twice).
  bool corner(const SurfaceMesh& s, int n) const {
    return junction_next[n].size() != 2 || node_faces[n].size() >= 3 || s.node_dim[n] <= 1 || on_seam[n];
  }
};

// The junction in chains from corner to corner (or closed on themselves).
std::vector<Chain> junction_chains(const SurfaceMesh& s, const Topology& topo);

// The chain's faces and its nodes sampled again to the size map: as many
// segments as the integral of 1/h along it (Eq. 1a-1b), each new node put on
// both surfaces.
void resample(Chain& c, const SurfaceMesh& s, const Topology& topo, const Geometry& g, const SizeField& h,
              double tol);

}  // namespace sizemesh::cut_faces_detail
