// Size sources: regions of space where the user wants a given element size
// whatever the geometry there (a wake, a tip vortex, a nacelle lip), as
// OpenVSP's point, line and box sources or Gmsh's Ball, Box and Cylinder
// fields give them.
//
// A source holds its size `size` inside its region and grows outside it:
// linearly to h_max over the distance `grow` when that is given (beyond it
// the source sets nothing), else at ln(beta) per unit length, the steepest
// the gradation allows (Eq. 12's bound), so that smoothing leaves it as set.
// Sources act on the initial sizes h_a (sizing/initial_sizes.h) with the
// other terms, so the map is still smoothed by Eq. 11/12 afterwards.
//
// Regions (model units):
//   point     within `radius` of `center`                (a ball: sphere is the same)
//   sphere    within `radius` of `center`
//   line      within `radius` of the segment from-to     (a capsule)
//   cylinder  within `radius` of the axis from-to, between its two end planes
//   box       inside the axis-aligned box min-max
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace sizemesh {

struct SizeSource {
  enum class Kind { Point, Sphere, Line, Cylinder, Box };
  Kind kind = Kind::Point;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();  // center | from, to | min, max
  double radius = 0;
  double size = 0;
  double grow = 0;  // 0: grow at ln(beta) per unit length

  // Distance from x to the region (0 inside).
  double distance(const Vec3& x) const;
  // The size this source asks at x, or infinity where it asks nothing.
  double size_at(const Vec3& x, double h_max, double log_beta) const;
  // "box min [x, y, z] max [x, y, z] size h" and the like, for messages and reports.
  std::string describe() const;
};

const char* source_kind_name(SizeSource::Kind k);

// A source from its command-line form, words separated by spaces:
//   point X Y Z R H [GROW]        sphere X Y Z R H [GROW]
//   line X0 Y0 Z0 X1 Y1 Z1 R H [GROW]   cylinder X0 Y0 Z0 X1 Y1 Z1 R H [GROW]
//   box XMIN YMIN ZMIN XMAX YMAX ZMAX H [GROW]
// Throws Error (one sentence naming the text) on anything else.
SizeSource parse_source(const std::string& text);

// Throws Error unless every number is finite, sizes positive, radii and grow
// not negative, a box's min not above its max and a cylinder's axis not of
// zero length. `what` names the source in the message.
void validate_source(const SizeSource& s, const std::string& what);

// The smallest size any of `sources` asks at each point (infinity where none does).
std::vector<double> source_sizes(const std::vector<SizeSource>& sources, const std::vector<Vec3>& points,
                                 double h_max, double log_beta);
double source_size(const std::vector<SizeSource>& sources, const Vec3& x, double h_max, double log_beta);

}  // namespace sizemesh
