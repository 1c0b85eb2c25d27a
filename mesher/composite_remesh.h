// Composite faces meshed as one domain (issue: virtual topology): the mesh
// of the B-rep faces re-meshed across the virtual curves of topology/, as
// surface remeshers with feature detection do (edge collapse, split, flip and
// tangential smoothing, every node projected back onto the exact B-rep).
// Nodes on virtual curves and at points where only virtual curves meet are
// free: they slide across the curve or merge into a neighbour, so a face
// narrower than the elements or a curve shorter than them leaves no sliver
// and no tiny element. Edges on feature curves, junctions and free
// boundaries stay; a node where a chain of them runs straight may merge into
// the next one along it (a composite curve discretised once), a corner never.
//
// Input:  s the final surface mesh (after the union), g the B-rep, h the size
//         map, topo its feature and virtual curves.
// Output: s re-meshed around its virtual curves; triangles keep the B-rep
//         face under their centroid, with uvs there; untouched triangles and
//         nodes keep their order.
// Work:   a few passes of local operations over the nodes within two rings
//         of a virtual curve, each over one star.
#pragma once

#include <array>
#include <unordered_set>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/surface_mesh.h"
#include "topology/topology.h"

namespace sizemesh {

struct CompositeRemeshResult {
  int virtual_nodes = 0;       // nodes the input had on virtual curves and points
  int virtual_nodes_left = 0;  // of those, still where they were
  int collapsed = 0, split = 0, flipped = 0, smoothed = 0;
  int slid = 0;                // nodes moved along a kept curve
  int attempts_crossing = 0;   // re-meshes undone because they crossed the surface (nodes there then frozen)
};

// junction: the union's junction edges (node pairs); their nodes stay, renumbered with s.
CompositeRemeshResult remesh_composites(SurfaceMesh& s, const Geometry& g, const SizeField& h, const Topology& topo,
                                        std::vector<std::array<int, 2>>* junction = nullptr);

// The edges of s the mesh keeps (edge_key): on feature curves, between
// composites, on free boundaries and non-manifold.
std::unordered_set<uint64_t> kept_edges(const SurfaceMesh& s, const Geometry& g, const Topology& topo);

}  // namespace sizemesh
