// The B-rep's tessellation by BRepMesh, handed on without kernel types: what
// the background mesh (background/background_mesh.h) is built from.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace sizemesh {

class Model;

// One face's triangulation (BRepMesh tessellates each face on its own; a curve
// is discretised once and its polygon appears in every face that uses it).
struct FaceTessellation {
  // One use of a curve by the face: its polygon's nodes (local ids) with the
  // curve parameter of each, in the polygon's order.
  struct CurveUse {
    int curve = 0;
    std::vector<int> nodes;
    std::vector<double> t;
  };
  std::vector<Vec3> xyz;                  // #n nodes in space
  std::vector<Vec2> uv;                   // #n nodes in the face's parameters
  std::vector<std::array<int, 3>> tris;   // local node ids, as the tessellation orders them
  std::vector<CurveUse> curves;           // the face's curve uses, in the face's edge order
};

// Per face (index face id - 1); a face without a usable triangulation (none,
// or without uv) has no triangles.
struct Tessellation {
  std::vector<FaceTessellation> faces;
};

struct BackgroundOptions {
  double deflection_rel = 1e-3;   // linear deflection / bounding-box diagonal
  double angle_deg = 20.0;        // angular deflection of the tessellation
};

// Tessellates the model with BRepMesh: the far field at ten times the
// deflection relative to its own size, the rest relative to the model's
// bounding-box diagonal. A curve whose discretisation OCCT fails on (a knot
// span standing still) is discretised again over the spans where it moves,
// so the faces along it are meshed too. Throws Error on bad options or a
// failed tessellation.
Tessellation tessellate(const Model& model, const BackgroundOptions& options);

}  // namespace sizemesh
