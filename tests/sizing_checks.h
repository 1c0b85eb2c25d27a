// A shape's model, background mesh and initial size map, shared by the size map's tests.
#pragma once

#include <TopoDS_Shape.hxx>

#include <utility>

#include "background/background_mesh.h"
#include "cad/occt_model.h"
#include "sizing/initial_sizes.h"

namespace sizemesh::test {

struct Sized {
  Model model;
  BackgroundMesh bg;
  SizeMap m;
};

inline Sized size_shape(const TopoDS_Shape& shape, const SizingParams& p) {
  Model model = model_from_shape(shape);
  BackgroundMesh bg = build_background_mesh(model);
  SizeMap m = initial_sizes(model, bg, p, model.info().diagonal());
  return {std::move(model), std::move(bg), std::move(m)};
}

}  // namespace sizemesh::test
