// Wing features found on the united surface: leading and trailing edges, and
// the local chord between them, for the chordwise spacings a CFD engineer
// asks at those curves (sizing: --le-spacing, --te-spacing, --aero).
//
// A trailing edge is a feature curve across which the surface turns by at
// least kTrailingTurnDeg (the two skins meet at a wedge of at most 60
// degrees). A leading edge is a smooth (crossed) curve on a composite face
// that also holds a trailing edge, running across the direction to that
// trailing edge (not along it), where the surface is curved far more than
// the chord: radius of curvature under a tenth of the distance to the
// trailing edge, and no shorter than 2% of it (a sliver of a curve near a
// sharp edge is no wing's leading edge). The chord at a point of one is its
// distance to the nearest point of the other kind on the same composite
// face.
//
// A blunt trailing edge is a base: a composite face that is a long narrow
// strip between two chains of feature curves (its creases with the upper and
// lower skins, the surface turning by kBaseTurnDeg or more across each),
// each chain at least kBaseAspect times as long as the strip is wide, the
// strip no wider than kBaseOverChord of the chord. Its creases are trailing
// edges of the skins they border, found with the sharp ones; a base counts
// when a leading edge lies on those skins. Its width at a point is the sum
// of the point's distances to the two chains.
//
// A tip is a cap at a wing's free end: a composite face, no base, every
// curve of whose border it shares with the skins (composites holding a
// leading edge) or a blunt base, an end of a leading edge on it. Its chord is the widest
// distance across it. A rounded tip (the skin wrapped round, the leading
// edge running on to the trailing edge) has no cap and no tip is found; an
// end joined to a body or cut by a symmetry plane is no tip.
//
// Found on B-rep curves only: a leading edge inside a face (a skin wrapped
// round its nose without a curve there) and a blunt trailing edge's base
// inside a face (behind C0 creases of the spline the preparation did not
// split, cad/fold_split.cpp) are not found.
//
// Inputs:  g the B-rep, t its topology (curve kinds, turns, composites).
// Output:  WingFeatures (below). Work: a few surface evaluations per curve.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "topology/topology.h"

namespace sizemesh {

struct WingFeatures {
  static constexpr double kTrailingTurnDeg = 120;
  static constexpr double kBaseTurnDeg = 45;
  static constexpr double kBaseAspect = 10;
  static constexpr double kBaseOverChord = 0.1;

  std::vector<int> leading, trailing;  // curve ids
  std::vector<int> leading_curve_composite, trailing_curve_composite;  // the composite face of each (a side's)
  // Points sampled along each kind's curves (chords are measured to them),
  // with the group of faces joined across smooth curves each lies on (the
  // composite face, whether or not the mesher joins them).
  std::vector<Vec3> leading_points, trailing_points;
  std::vector<int> leading_composite, trailing_composite;
  double leading_length = 0, trailing_length = 0;
  double chord_min = 0, chord_max = 0;  // over the samples of both kinds
  // Blunt trailing edges: per base, its B-rep faces and its two crease
  // chains as polylines (sampled points in order along each curve).
  struct Base {
    std::vector<int> faces;
    std::vector<std::vector<Vec3>> side[2];  // polylines of each chain's curves
    double width_min = 0, width_max = 0;     // over the samples of both chains
  };
  std::vector<Base> bases;
  // Wing tips: the B-rep faces of each cap and its chord.
  struct Tip {
    std::vector<int> faces;
    double chord = 0;
  };
  std::vector<Tip> tips;

  bool empty() const { return leading.empty() && trailing.empty(); }
  // Distance from x on composite `composite` to the nearest sample of the
  // other kind there (a leading edge's chord when `leading`); 0 where none.
  double chord_at(const Vec3& x, int composite, bool leading) const;
  // Width of base `b` at x: its distances to the two chains, summed.
  double base_width_at(const Vec3& x, int b) const;
};

WingFeatures find_wing_features(const Geometry& g, const Topology& t);

}  // namespace sizemesh
