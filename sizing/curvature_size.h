// Curvature size per background vertex (paper 3.2.1): h_c = 2 r sin(phi_c / 2)
// with r = 1 / k, k the largest absolute principal curvature over every face
// the vertex lies on (at its uv there), and for vertices on curves also the
// curve's own curvature. Local phi_c per face and per curve apply where set.
// Beyond the paper, an optional deviation bound delta (p.deviation > 0) caps it
// by the chord whose height off the arc is delta: 2 sqrt(2 r delta - delta^2),
// on faces with r from triangle_deviation_curvature (an element's centre is
// further off a doubly curved face than the middles of its sides). Under the
// bound, radii r <= delta set no size (the whole arc lies within delta of its
// chord) and phi_c's size is at least 2 delta (a chord of 2 delta lies within
// delta of any larger arc).
//
// Inputs:  g geometry, bg background mesh, p parameters (phi_c, local phi_c)
// Output:  #V sizes, kNoLimit where the surface is flat or the curvature is
//          undefined (poles, apexes, evaluation failures): never 0 or NaN.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "core/size_field.h"  // deviation_size, face_deviation_size
#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

// Face curvature sizes already computed, by face and the exact bits of uv:
// the background refinement asks them again every round at the vertices,
// edge midpoints and triangle samples its splits left as they were. A value
// comes from face_curvature_size alone, so the memo changes no size.
class CurvatureMemo {
 public:
  // face_curvature_size(g, face, uv, p), from the memo when it was asked before.
  double face(const Geometry& g, int face, const Vec2& uv, const SizingParams& p);
  // Only a look-up (safe while other threads look up too): false when absent.
  bool find(int face, const Vec2& uv, double& h) const;
  void add(int face, const Vec2& uv, double h);

 private:
  struct Key {
    int face;
    uint64_t u, v;
    bool operator==(const Key& o) const { return face == o.face && u == o.u && v == o.v; }
  };
  struct Hash {
    size_t operator()(const Key& k) const;
  };
  static Key key(int face, const Vec2& uv);
  std::unordered_map<Key, double, Hash> sizes_;
};

// memo: optional; faces' sizes are taken from it and added to it.
std::vector<double> curvature_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p,
                                    CurvatureMemo* memo = nullptr);

// 2 r sin(phi/2) for curvature k (1/length) and phi in degrees; kNoLimit for k <= 0.
double chord_size(double k, double phi_deg);
// The curvature whose arc's chord h lies as far off it as an equilateral
// triangle of side h lies off a surface of principal curvatures k1, k2:
// max(|k1|, 2/3 |k1 + k2|) (|k1| >= |k2|; 4/3 k on a sphere, k on a cylinder).
double triangle_deviation_curvature(double k1, double k2);

// The curvature size at one point of a face, and of a curve (kNoLimit where flat or undefined).
double face_curvature_size(const Geometry& g, int face, const Vec2& uv, const SizingParams& p);
double curve_curvature_size(const Geometry& g, int curve, double t, const SizingParams& p);

}  // namespace sizemesh
