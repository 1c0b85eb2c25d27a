// The run report: printed summary and --report JSON (mesh counts, min-angle
// histogram, bad (< 12 deg) and low-quality (< 24 deg) triangles as the paper
// counts them, size conformity, boundary and non-manifold edges, time per
// stage, mean background triangles visited per size query, failed faces).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cad/model.h"
#include "mesher/composite_remesh.h"
#include "topology/virtual_reasons.h"
#include "topology/wing_features.h"
#include "mesher/cut_faces.h"
#include "mesher/mesh_union.h"
#include "mesher/quality.h"
#include "mesher/surface_mesh.h"
#include "sizing/refine_background.h"
#include "sizing/size_map.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"

namespace sizemesh {

struct RunReport {
  const Model* model = nullptr;
  int background_triangles = 0, background_vertices = 0;
  double estimated_triangles = 0;  // from the size map, before meshing
  const SizeMap* sizes = nullptr;
  RefineStats refinement;
  SmoothStats smoothing;
  const SurfaceMesh* mesh = nullptr;
  MeshQuality quality;
  // Triangles whose target size (mean of their nodes') is within 5% of h_min,
  // as shares of the triangles and of the area: how much h_min drives the mesh.
  double at_h_min_share = 0, at_h_min_area_share = 0;
  QueryStats queries;
  MeshUnionResult mesh_union;  // components united at mesh level (none when every union was a B-rep one)
  CutFacesResult cut_faces;    // the faces that union cut, meshed again
  const Topology* topology = nullptr;
  const WingFeatures* wing = nullptr;  // leading and trailing edges found
  CompositeRemeshResult composite;  // the mesh re-meshed across virtual curves
  VirtualReasons virtual_reasons;   // why each crossed curve was in the way
  std::vector<std::pair<std::string, double>> seconds;  // stage, wall time
  std::vector<std::pair<std::string, long long>> evaluations;  // stage, surface evaluations in it
};

nlohmann::json report_json(const RunReport& r);
void print_mesh_summary(const RunReport& r, std::ostream& out);
void write_report(const std::string& path, const RunReport& r);

}  // namespace sizemesh
