// The size map on the background vertices: every criterion kept apart so a
// user can see why each size is what it is.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace sizemesh {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// What set a vertex's initial size h_a (paper 3.4).
// FarField: the own size of the far field and the symmetry plane (in place of h_max).
// Source: a size source (sizing/sources.h). Aero: a leading or trailing
// edge's chordwise spacing (--le-spacing, --te-spacing).
enum class Limit : int8_t {
  HMax = 0, Curvature, FaceProximity, CurveLength, Gap, Thickness, User, HMin, FarField, Source, Aero
};
constexpr int kNumLimits = 11;
const char* limit_name(Limit l);

struct SizeMap {
  // Per background vertex (#V); kNoLimit where a criterion sets no bound.
  std::vector<double> h_curvature;  // h_c = 2 r sin(phi_c / 2)             (paper 3.2.1)
  std::vector<double> h_proximity;  // h_d = min(h_d1, h_d0, gap / mu_d)    (paper 3.2.2, plus gaps)
  std::vector<double> h_user;       // h_u prescribed sizes                 (paper 3.4)
  std::vector<double> h_source;     // h_s size sources (sizing/sources.h)
  std::vector<double> h_aero;       // spacing share times chord on leading and trailing edges (not floored by h_min)
  std::vector<double> h_initial;    // h_a = min(h_aero, max(h_min, min(h_d, h_c, h_u, h_s, h_max)))
  std::vector<double> h;            // smoothed (after smooth()); starts as h_initial
  std::vector<Limit> limit;         // which term gave h_a
  std::vector<double> h_cap;        // the largest size allowed: h_max, or the least of its faces' own
  // Per background edge (#E) and triangle (#T): ln(beta) bound of the gradation.
  std::vector<double> edge_log_beta, tri_log_beta;
  double h_min = 0, h_max = 0;
  // Timings of the steps that built the map (seconds).
  double t_curvature = 0, t_proximity = 0, t_gap = 0, t_user = 0;
};

}  // namespace sizemesh
