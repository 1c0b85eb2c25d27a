// Composite faces and curves over the B-rep (virtual topology): which curves
// the mesh must follow and which it may cross.
//
// A curve is a *feature*, kept hard, where the surface turns across it by
// more than the feature angle (a trailing edge, a wing-body junction, a box
// edge), where the faces it separates belong to different classes (another
// component, the far field or the symmetry plane, a face with its own user
// settings), where it bounds one face only or more than two, or where the
// user asks. Every other curve is *virtual*: the faces on its two sides are
// one composite face, and the mesh crosses it freely (its nodes may leave
// it or vanish), so narrow faces, short curves and curves meeting at small
// angles on a smooth surface no longer set the mesh. A seam (one face on both
// sides) is virtual by nature. Feature curves meeting at a point where no
// other feature starts and they turn by less than the feature angle form one
// composite curve: the point is not a corner.
//
// Inputs:  g the B-rep, face_class per face id (index f - 1; faces of
//          different classes never merge), hard_curves curve ids the user
//          keeps, feature_angle_deg.
// Output:  Topology (below).
// Work:    a few surface evaluations per curve.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace sizemesh {

enum class CurveKind : unsigned char {
  Virtual = 0,   // smooth, between faces of one class: crossed by the mesh
  Seam,          // one face on both sides
  Angle,         // the surface turns across it by more than the feature angle
  Marker,        // between faces of different classes
  User,          // kept by the user
  Boundary,      // bounds one face only (a free edge) or more than two
  Degenerate,    // of zero length (a pole)
};
const char* curve_kind_name(CurveKind k);

struct Topology {
  bool enabled = false;             // false: every curve is hard (--no-composite)
  double feature_angle_deg = 30;
  std::vector<CurveKind> curve_kind;  // [c - 1]
  std::vector<double> curve_turn_deg; // [c - 1] largest turn of the normal across it; -1 where undefined
  std::vector<int> face_composite;    // [f - 1] composite id, 1-based
  int composites = 0;
  int composite_curves = 0;           // chains of feature curves through smooth points
  std::vector<char> point_corner;     // [p - 1] 1 where feature curves meet at a corner
  std::vector<double> chain_length;   // [c - 1] length of the composite curve a feature curve is part of

  // True when the mesh must keep its nodes on curve c.
  bool hard(int curve) const {
    if (!enabled || curve < 1 || curve > static_cast<int>(curve_kind.size())) return true;
    const CurveKind k = curve_kind[curve - 1];
    return k != CurveKind::Virtual && k != CurveKind::Seam && k != CurveKind::Degenerate;
  }
  int composite_of(int face) const {
    return face >= 1 && face <= static_cast<int>(face_composite.size()) ? face_composite[face - 1] : face;
  }
  int count(CurveKind k) const;
};

Topology build_topology(const Geometry& g, const std::vector<int>& face_class, const std::set<int>& hard_curves,
                        double feature_angle_deg, bool enabled = true);

}  // namespace sizemesh
