// OpenCASCADE side of Model; included only by geometry/*.cpp and tests that build shapes.
#pragma once

#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include "geometry/model.h"

namespace sizemesh {

// Per-face data cached at load time (thread-safe to evaluate: Geom objects only).
struct OcctFace {
  Handle(Geom_Surface) surface;  // with the face's location applied
  bool reversed = false;
  UVBox uv_bounds;
  double period_u = 0, period_v = 0;
  double area = 0, boundary_length = 0;
  std::vector<FaceLoop> loops;
};

struct OcctPCurve {
  int face = 0, side = 0;
  Handle(Geom2d_Curve) curve;
};

struct OcctCurve {
  Handle(Geom_Curve) curve;  // null for degenerated edges
  double t0 = 0, t1 = 0;
  bool degenerated = false;
  double length = 0;
  int start_point = 0, end_point = 0;
  std::vector<OcctPCurve> pcurves;
};

struct Model::Impl {
  TopoDS_Shape shape;
  TopTools_IndexedMapOfShape faces, edges, vertices, solids, shells;
  ModelInfo info;
  std::vector<std::string> face_names;
  std::vector<OcctFace> face_data;    // index id - 1
  std::vector<OcctCurve> curve_data;  // index id - 1
};

// Sews (when asked and needed), numbers the entities and caches per-entity data.
// `info` carries what the reader knew (path, format, unit); `names` maps
// shapes as read to their names in the file.
Model model_from_shape(const TopoDS_Shape& shape, ModelInfo info, const LoadOptions& options,
                       const std::vector<std::pair<TopoDS_Shape, std::string>>& names = {});

// For shapes built in code (tests, examples): unit "unknown", format "shape".
Model model_from_shape(const TopoDS_Shape& shape, const LoadOptions& options = {});

}  // namespace sizemesh
