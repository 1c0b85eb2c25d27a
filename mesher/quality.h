// Quality report of a surface mesh: shape, topology, validity against the
// surface, size conformity and area.
//
// Inputs:
//   m   the mesh (mesh_surface())
//   g   the B-rep it was made from (surface normals, node distances)
//   h   the size function it was made for (size conformity, via at_xyz)
// Output (MeshQuality):
//   min angle per triangle summarised as a histogram of 6-degree bins
//   (bin k holds [6k, 6k+6)), counts below 12 and 24 degrees; boundary edges
//   (in one triangle), non-manifold edges (in three or more), orientation
//   conflicts (an edge of two triangles used twice in one direction); inverted triangles
//   (normal against the oriented surface normal) and zero-area triangles;
//   largest distance of a node from its face's surface; share of edges with
//   length / h(midpoint) in [1/sqrt2, sqrt2]; total area.
//   Triangles under 12 degrees split into forced ones and avoidable ones
//   (curves and corners are those of the united surface: a junction where a
//   union of meshes cut two faces counts as the curve a B-rep union makes
//   there, a node where it meets a curve as a B-rep point): at a
//   B-rep point where the face's own corner (the angle sum of its triangles
//   there) is under 12 degrees, a triangle whose smallest angle sits at that
//   point, or whose nodes all lie on the two curves meeting there (spanning
//   the corner's narrow wedge), is forced by the CAD; so is a triangle with
//   every node on its face's boundary whose shortest edge spans the face (an
//   edge inside the face, not a boundary segment) at under h tan(12 deg) (a
//   face, or the fold of a curve turning back on itself, narrower than the
//   elements), and one whose
//   shortest edge, under h tan(12 deg), is a segment of a B-rep curve itself
//   shorter than h (a CAD curve shorter than the elements, e.g. one split
//   only because it turns sharply), or a junction's whole piece between two
//   corners (a cut passing a B-rep point close by).
//   Self-intersecting triangle pairs (mesher/self_intersection.h), and of those
//   the local ones: within one face or between faces that share a curve.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "core/geometry.h"
#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

struct MeshQuality {
  int triangles = 0, nodes = 0;
  std::vector<double> min_angle;          // per triangle (degrees)
  std::vector<int8_t> sliver;             // per triangle: 0 not under 12 degrees, 1 forced, 2 avoidable
  std::array<int, 10> histogram{};        // of min_angle, 6-degree bins
  int below_12 = 0, below_24 = 0;
  int forced_below_12 = 0;                // at a CAD corner under 12 degrees, across a narrow face or on a short curve
  int narrow_below_12 = 0;                // of those, spanning a face narrower than h tan(12 deg)
  int short_curve_below_12 = 0;           // of those, on a segment under h tan(12 deg) of a curve shorter than h
  int avoidable_below_12 = 0;             // below_12 - forced_below_12
  // Under 12 degrees with the smallest angle at a corner where kept edges
  // (feature curves, junctions, free boundaries) meet at under 12 degrees:
  // forced by the shape. The rest are the slivers a user sees.
  int feature_corner_below_12 = 0;
  double worst_angle = 180;
  int boundary_edges = 0, nonmanifold_edges = 0, orientation_conflicts = 0;
  std::vector<int> open_faces;            // faces at boundary or non-manifold edges (first 20, ascending)
  int inverted = 0, zero_area = 0;
  std::vector<int> inverted_faces;        // faces holding inverted triangles (first 20 met)
  long long self_intersections = 0;       // pairs of triangles meeting beyond shared nodes
  long long local_self_intersections = 0; // of those, in one face or faces sharing a curve
  std::vector<std::array<int, 2>> intersecting_faces;  // face pairs with local intersections (first 20)
  std::vector<std::array<int, 2>> crossing_faces;      // face pairs with the other intersections (first 20)
  double max_inner_node_distance = 0;     // nodes inside faces, from their surface
  double max_node_distance = 0;           // every node, from the nearest surface of its triangles' faces at its uv there
  double size_conformity = 0;             // share of edges of conforming length
  double area = 0;
};

// kept: the edges the mesh keeps (kept_edges); without them no triangle is
// counted at a feature corner.
MeshQuality mesh_quality(const SurfaceMesh& m, const Geometry& g, const SizeField& h,
                         const std::unordered_set<uint64_t>* kept = nullptr);

// Triangle t of m is inverted: its normal and its face's surface normal at
// its uv centroid (oriented as in the shell) point apart.
bool inverted_triangle(const SurfaceMesh& m, const Geometry& g, size_t t);

}  // namespace sizemesh
