// One face meshed inside its boundary: the advancing front's strategies, ear filling, the optimiser.
//
// Internal to the surface mesher (mesher/mesh_surface.cpp, and mesh_within()).
#pragma once

#include <string>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/discretise_curves.h"
#include "mesher/face_mesh.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::mesh_surface_detail {

struct FaceResult {
  FaceMesh mesh;
  bool ok = false;
  std::string reason;
  long long size_queries = 0;
  int fronts_3d = 0;
  int strategy = 0;  // front strategy that closed the face
  long long front_steps = 0;
  long long front_work = 0;  // front edges and nodes looked at, over its strategies
  bool filled = false;  // the front's leftover was closed by ear clipping
  bool lenient = false; // the strict run left a hole: meshed by the lenient one
  double seconds_front = 0, seconds_optimise = 0;
  // Surface evaluations: the face's setup (uv stretch, boundary), the front
  // (every strategy tried), the optimisation.
  long long evaluations_setup = 0, evaluations_front = 0, evaluations_optimise = 0;
};

// One face, start to end; a face the geometry cannot mesh is returned with its
// reason, not thrown (only a bug escapes).
FaceResult mesh_face(const Geometry& g, const SizeField& h, const CurveMesh& cm, int face, const MeshOptions& o);

}  // namespace sizemesh::mesh_surface_detail
