// The surface mesher (paper 4.1), top level: discretise every curve once,
// mesh every face in its uv domain in parallel, improve, and assemble one
// conforming mesh whose nodes on B-rep points and curves are shared by index.
//
// Inputs:
//   g   the B-rep (thread-safe)
//   h   the size function (thread-safe)
//   o   thread count and optimisation passes
// Output: SurfaceMesh (mesher/surface_mesh.h). A face that cannot be meshed is
// listed in failures and left out; the rest is kept. The mesh does not depend
// on the thread count.
#pragma once

#include "geometry/geometry.h"
#include "mesher/surface_mesh.h"
#include "sizing/size_function.h"

namespace sizemesh {

SurfaceMesh mesh_surface(const Geometry& g, const SizeFunction& h, const MeshOptions& o = {});

}  // namespace sizemesh
