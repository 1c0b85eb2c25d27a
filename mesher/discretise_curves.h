// Curve discretisation into a unit mesh (paper 2.1, Eq. 1a-1b), done once per
// B-rep curve and shared by every face that uses it.
//
// Inputs:
//   g   the B-rep
//   h   size function, sampled along each curve through one face's pcurve
// Outputs (CurveMesh):
//   point_node  #points+1 node id of each B-rep point (index by point id; [0] unused)
//   curves      #curves+1 per curve: parameters t and node ids of its nodes
//               from t0 to t1 (ends are the point nodes; degenerate curves: empty)
//   xyz, node_dim, node_entity  the nodes created (points first, then curve nodes)
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"

namespace sizemesh {

struct CurveNodes {
  std::vector<double> t;   // n+1 parameters, t.front() = t0, t.back() = t1
  std::vector<int> node;   // n+1 node ids
};

struct CurveMesh {
  std::vector<int> point_node;
  std::vector<CurveNodes> curves;
  std::vector<Vec3> xyz;
  std::vector<int8_t> node_dim;
  std::vector<int> node_entity;
  long long size_queries = 0;
};

// Segment count and node placement per curve: n = max(1, round(integral ds/h))
// (Eq. 1a), nodes at equal steps of that integral (Eq. 1b). Beyond the paper,
// for valid loops in uv when h exceeds a curve's radius: no segment turns more
// than 60 degrees, closed curves and boundary loops get at least 3 segments,
// and the curves of a sharp corner start with one long segment
// (mesher/sharp_corners.h).
// Degenerate curves (poles) get none.
// The size field's deviation bound (h.accuracy(); 0: none) bounds corner_leads' first segments.
CurveMesh discretise_curves(const Geometry& g, const SizeField& h);

}  // namespace sizemesh
