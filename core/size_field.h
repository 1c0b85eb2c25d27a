// What the mesher asks of a size map (sizing/ builds one, mesher/ reads it and
// includes nothing else of sizing/): the wanted element size at a point, and
// the accuracy rules the map was built with, which the mesher keeps where its
// own steps (a sharp corner's first segment, a split for turning, sizes along
// a junction the map never saw) decide lengths the map cannot answer alone.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "core/types.h"

namespace sizemesh {

class Geometry;

// The accuracy rules of a size map (SizingParams, sizing/params.h, resolved
// for one model by accuracy_rules()); all zero: none.
struct AccuracyRules {
  // Largest distance of the mesh off the surface (model units): a sharp
  // corner's first segment on a curved face stays within it.
  double deviation = 0;
  // The map's floor: a split for turning leaves no edge under it.
  double h_min = 0;
  // Per face (index face id), the angle in radians an inner edge may turn
  // along the surface (phi_c): an edge the front left over its size on a
  // curved face whose chord cuts deeper than that is split.
  std::vector<double> max_turn;
  // Per face (index face id), the bound on the size's gradient, ln(beta)
  // (Eq. 12): sizes met along a junction the map never saw grow away from it
  // no faster.
  std::vector<double> size_slope;

  double turn(int face) const { return face >= 0 && face < static_cast<int>(max_turn.size()) ? max_turn[face] : 0.0; }
};

class SizeField {
 public:
  virtual ~SizeField() = default;
  // Size at uv on a face (1-based id). `hint` is the caller's search start:
  // pass -1 when there is none; it is updated for the next nearby query.
  // Safe to call from several threads, each with its own hint.
  virtual double at(int face, const Vec2& uv, int& hint) const = 0;
  // Size at a point in space, for callers with no face or uv.
  virtual double at_xyz(const Vec3& xyz) const = 0;

  const AccuracyRules& accuracy() const { return accuracy_; }
  void set_accuracy(AccuracyRules rules) { accuracy_ = std::move(rules); }

  // The longest chord on `face` at uv that lies within the deviation bound of
  // the surface there (face_deviation_size); infinity where there is no bound
  // or the surface is flat or its curvature cannot be evaluated.
  double deviation_chord(const Geometry& g, int face, const Vec2& uv) const;

  // Edge lengths against the size: the questions the mesh operations ask
  // (mesher/ops/split.h), as CGAL's remeshing asks its sizing field whether
  // an edge is too long and where to split it. Lengths in model units.

  // An edge is too long over kSplitAbove times the size wanted along it.
  static constexpr double kSplitAbove = 1.4;
  // An edge up to 1.4 curvature sizes long turns by 1.4 phi_c and cuts twice as
  // deep as phi_c allows (height ~ length^2); 1.25 keeps it within 1.6 times.
  // Edges under 1.1 sizes are left alone, and so are those a split would cut
  // under h_min: there a small radius turns every edge by more than phi_c, and
  // h_min is the user's word on how small to go.
  static constexpr double kTurnSlack = 1.25;
  static constexpr double kTurnSplitAbove = 1.1;

  // The size wanted along an edge whose ends want h_a and h_b: their geometric mean.
  double size_along(double h_a, double h_b) const { return std::sqrt(h_a * h_b); }
  // An edge's length in units of the longest it may be (kSplitAbove times
  // the size h wanted along it): over 1, it is too long, and by how much
  // orders the splits. 0 where h is not positive (no size to compare with).
  double length_excess(double len, double h) const { return h > 0 ? len / (kSplitAbove * h) : 0; }
  // Long enough to split for turning along the surface: over kTurnSplitAbove
  // sizes h, and its halves not under the floor h_min.
  bool may_split_for_turn(double len, double h, double h_min) const {
    return h > 0 && len > kTurnSplitAbove * h && len >= 2 * h_min;
  }
  // How far an edge of length len whose middle lies `height` off the surface
  // turns along it, in units of kTurnSlack max_turn (radians): over 1, too
  // much (a chord of length l whose middle lies s off the surface turns by
  // about 8 s / l).
  double turn_excess(double height, double len, double max_turn) const {
    return 8 * height / len / (kTurnSlack * max_turn);
  }
  // Where an edge with ends at ua and ub (uv) is split: its uv midpoint.
  Vec2 split_point(const Vec2& ua, const Vec2& ub) const { return 0.5 * (ua + ub); }

 private:
  AccuracyRules accuracy_;
};

// A uniform size everywhere (tests, and a fallback for debugging).
class UniformSize final : public SizeField {
 public:
  explicit UniformSize(double h) : h_(h) {}
  double at(int, const Vec2&, int&) const override { return h_; }
  double at_xyz(const Vec3&) const override { return h_; }

 private:
  double h_;
};

// Chord of an arc of curvature k whose height is delta: 2 sqrt(2 r delta - delta^2)
// (2 r when delta >= r); infinity for k <= 0 or delta <= 0.
double deviation_size(double k, double delta);
// deviation_size of a face's largest curvature at uv; NaN where the kernel
// cannot evaluate the curvature there (the caller decides what that means).
double face_deviation_size(const Geometry& g, int face, const Vec2& uv, double delta);

}  // namespace sizemesh
