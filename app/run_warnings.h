// The checks and warning lines of a run (app/stages.h): each looks at what a
// stage made and says, in one line, what the user should know or do.
#pragma once

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "io/report.h"
#include "mesher/quality.h"
#include "mesher/surface_mesh.h"
#include "sizing/size_map.h"
#include "sizing/triangle_estimate.h"

namespace sizemesh {

// Called with each warning as it arises (the command prints it at once).
using WarningSink = std::function<void(const std::string&)>;

// The union was asked for and the model has a closed body, not half a
// model: the mesh must be one closed surface. Open sheets imprinted on the
// bodies leave it open; alone, or as half a model, they are what the model is.
inline bool closed_expected(const Preparation& p) {
  if (!p.union_requested || p.union_skipped || p.half_model_axis >= 0) return false;
  return std::any_of(p.components.begin(), p.components.end(), [](const Component& c) { return c.role == "solid"; });
}

// Refuses (throws Error) a size map that asks for more triangles than the
// user allows, naming the option that drives the count.
void check_triangle_budget(const TriangleEstimate& e, double max_triangles, const SizeMap& h);

// Triangles crossing within a face or across a shared curve: the front never
// makes them where the CAD is sound, so they point at faces that cross
// themselves or their neighbours.
void warn_local_intersections(const MeshQuality& q, const WarningSink& warn);
// Triangles of faces that share no curve crossing each other where the
// components were united: the surface is not one closed body (exit 3).
void warn_crossings(const MeshQuality& q, const Preparation& p, const WarningSink& warn);
// Boundary or non-manifold edges where one closed surface was asked for,
// every face meshed and every component united (exit 3).
void warn_open(const MeshQuality& q, const Preparation& p, bool faces_failed, const WarningSink& warn);
// Shares of the triangles and of the area whose target size is within 5% of h_min.
// Triangles asked below h_min (a leading edge's chordwise spacing, a
// source) or at a node sized by such a request are the user's, not h_min's:
// not counted. `limited_by` per node (sizing/limit_at.h), may be empty.
void measure_h_min(const SurfaceMesh& m, const std::vector<double>& target, const std::vector<double>& limited_by,
                   double h_min, RunReport& r);
// One warning line when h_min sets more than 5% of the triangles.
void warn_h_min(const RunReport& r, double h_min, const WarningSink& warn);
// Faces the B-rep tessellation left without a background mesh: their sizes
// are the nearest other face's.
void warn_faces_without_background(const BackgroundMesh& bg, const WarningSink& warn);
// One line naming the components the union left out (the run ends with exit 3).
void warn_not_united(const Preparation& p, const WarningSink& warn);
// One line naming the open components left out of the wetted surface,
// `one`/`many` saying what they are and `why` where they lie.
void warn_left_out(const std::vector<int>& ks, const char* one, const char* many, const char* why,
                   const WarningSink& warn);

}  // namespace sizemesh
