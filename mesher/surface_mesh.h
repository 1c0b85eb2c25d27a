// The result of surface meshing (paper 4.1): one conforming triangle mesh of all faces.
//
// Outputs of mesh_surface():
//   xyz          #nodes positions (model space)
//   node_dim     #nodes classification dimension: 0 B-rep point, 1 curve, 2 face
//   node_entity  #nodes id (1-based) of that point, curve or face
//   tris         #tris node triples, oriented as the face lies in its shell
//                (outward for closed solids)
//   tri_face     #tris face id of each triangle
//   tri_uv       #tris uv of each corner in its face (for checks against the surface)
//   failures     faces that could not be meshed; their triangles are left out
//   stats        seconds per stage and size queries made
#pragma once

#include <array>
#include <functional>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace sizemesh {

struct MeshStats {
  double seconds_curves = 0;    // wall time: curve discretisation (paper 2.1)
  double seconds_faces = 0;     // wall time: the parallel face stage (front + optimisation)
  double seconds_front = 0;     // summed over faces: advancing front
  double seconds_optimise = 0;  // summed over faces: swaps and smoothing
  long long size_queries = 0;   // calls of SizeField::at / at_xyz
  // Surface evaluations summed over faces: setup (uv stretch, boundary), front, optimisation.
  long long evaluations_setup = 0, evaluations_front = 0, evaluations_optimise = 0;
  int fronts_3d = 0;            // ideal points computed in 3D and projected (Tremel 1)
  long long front_steps = 0;    // tries at front edges, over every face and strategy
  long long front_work = 0;     // front edges and nodes those tries looked at
  int faces_retried = 0;        // faces whose front got stuck and were meshed again
  int faces_relaxed = 0;        // of those, faces that needed the last-resort strategies
  int faces_lenient = 0;        // of those, faces only a lenient run closed (may hold inverted triangles)
  int faces_filled = 0;         // faces whose front's leftover was closed by ear clipping
  int shared_edges_flipped = 0;  // inner edges two faces both meshed, flipped in one (flip_shared_inner_edges)
  int back_to_back_dropped = 0; // triangles dropped in pairs where two faces lie back to back (no thickness)
};

struct SurfaceMesh {
  std::vector<Vec3> xyz;
  std::vector<int8_t> node_dim;
  std::vector<int> node_entity;

  std::vector<std::array<int, 3>> tris;
  std::vector<int> tri_face;
  std::vector<std::array<Vec2, 3>> tri_uv;

  struct Failure {
    int face;
    std::string reason;
  };
  std::vector<Failure> failures;

  MeshStats stats;
};

struct MeshOptions {
  int threads = 0;           // 0: all hardware threads
  int optimise_passes = 3;   // swap + smoothing passes per face
  // Triangles the size map asks for per face (index face id; estimated by the sizing stage):
  // the face mesher's work budget. Empty: budgets from the boundary alone.
  std::vector<double> expected_triangles;
  // Face f's entry, 0 when there is none.
  double expected(int f) const {
    return f >= 0 && f < static_cast<int>(expected_triangles.size()) ? expected_triangles[f] : 0.0;
  }
  // (The accuracy rules the size map was built with travel with it: SizeField::accuracy().)
  // Called after each face with (faces done, faces in all), from any thread.
  std::function<void(int, int)> on_face_done;
};

}  // namespace sizemesh
