#include "sizing/sources.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sizing/size_map.h"

namespace sizemesh {
namespace {

std::string point_text(const Vec3& p) {
  std::ostringstream s;
  s << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  return s.str();
}

// Distance from x to the segment ab.
double segment_distance(const Vec3& a, const Vec3& b, const Vec3& x) {
  const Vec3 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((x - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (x - a - t * d).norm();
}

}  // namespace

const char* source_kind_name(SizeSource::Kind k) {
  switch (k) {
    case SizeSource::Kind::Point: return "point";
    case SizeSource::Kind::Sphere: return "sphere";
    case SizeSource::Kind::Line: return "line";
    case SizeSource::Kind::Cylinder: return "cylinder";
    case SizeSource::Kind::Box: return "box";
  }
  return "?";
}

double SizeSource::distance(const Vec3& x) const {
  switch (kind) {
    case Kind::Point:
    case Kind::Sphere: return std::max(0.0, (x - a).norm() - radius);
    case Kind::Line: return std::max(0.0, segment_distance(a, b, x) - radius);
    case Kind::Cylinder: {
      const Vec3 axis = b - a;
      const double length = axis.norm();
      const Vec3 u = axis / length;
      const double t = (x - a).dot(u);
      const double across = (x - a - t * u).norm();
      const double out_radial = std::max(0.0, across - radius);
      const double out_axial = std::max({0.0, -t, t - length});
      return std::hypot(out_radial, out_axial);
    }
    case Kind::Box: {
      const Vec3 out = (a - x).cwiseMax(x - b).cwiseMax(Vec3::Zero());
      return out.norm();
    }
  }
  return std::numeric_limits<double>::infinity();
}

double SizeSource::size_at(const Vec3& x, double h_max, double log_beta) const {
  const double d = distance(x);
  if (!(d > 0)) return size;
  if (grow > 0) return d < grow ? size + (std::max(h_max, size) - size) * d / grow : kNoLimit;
  // At the gradation's own rate (Eq. 12: h grows by at most ln(beta) per unit length).
  return size + log_beta * d;
}

std::string SizeSource::describe() const {
  std::ostringstream s;
  s << source_kind_name(kind) << " ";
  switch (kind) {
    case Kind::Point:
    case Kind::Sphere: s << "center " << point_text(a) << " radius " << radius; break;
    case Kind::Line:
    case Kind::Cylinder: s << "from " << point_text(a) << " to " << point_text(b) << " radius " << radius; break;
    case Kind::Box: s << "min " << point_text(a) << " max " << point_text(b); break;
  }
  s << " size " << size;
  if (grow > 0) s << " grow " << grow;
  return s.str();
}

SizeSource parse_source(const std::string& text) {
  std::istringstream in(text);
  std::string word;
  in >> word;
  std::vector<double> v;
  std::string token;
  auto fail = [&](const std::string& why) {
    return Error("--source '" + text + "': " + why +
                 " (point|sphere X Y Z R H [GROW], line|cylinder X0 Y0 Z0 X1 Y1 Z1 R H [GROW], "
                 "box XMIN YMIN ZMIN XMAX YMAX ZMAX H [GROW])");
  };
  while (in >> token) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(token, &used);
    } catch (const std::logic_error&) {
      used = 0;
    }
    if (used != token.size()) throw fail("'" + token + "' is not a number");
    v.push_back(x);
  }
  SizeSource s;
  size_t n = 0;  // numbers before the size and the optional grow
  if (word == "point" || word == "sphere") {
    s.kind = word == "point" ? SizeSource::Kind::Point : SizeSource::Kind::Sphere;
    n = 4;
  } else if (word == "line" || word == "cylinder") {
    s.kind = word == "line" ? SizeSource::Kind::Line : SizeSource::Kind::Cylinder;
    n = 7;
  } else if (word == "box") {
    s.kind = SizeSource::Kind::Box;
    n = 6;
  } else {
    throw fail("unknown kind '" + word + "'");
  }
  if (v.size() != n + 1 && v.size() != n + 2)
    throw fail("takes " + std::to_string(n + 1) + " or " + std::to_string(n + 2) + " numbers, got " +
               std::to_string(v.size()));
  s.a = Vec3(v[0], v[1], v[2]);
  if (n == 7 || n == 6) s.b = Vec3(v[3], v[4], v[5]);
  if (n == 4) s.radius = v[3];
  if (n == 7) s.radius = v[6];
  s.size = v[n];
  if (v.size() == n + 2) s.grow = v[n + 1];
  validate_source(s, "--source '" + text + "'");
  return s;
}

void validate_source(const SizeSource& s, const std::string& what) {
  auto bad = [&](const std::string& why) { return Error(what + ": " + why); };
  if (!s.a.allFinite() || !s.b.allFinite() || !std::isfinite(s.radius) || !std::isfinite(s.grow))
    throw bad("every coordinate, radius and grow must be finite");
  if (!(s.size > 0) || !std::isfinite(s.size)) throw bad("size must be positive");
  if (!(s.radius >= 0)) throw bad("radius must not be negative");
  if (!(s.grow >= 0)) throw bad("grow must not be negative");
  if (s.kind == SizeSource::Kind::Box && !(s.a.array() <= s.b.array()).all())
    throw bad("the box's min must not be above its max");
  if (s.kind == SizeSource::Kind::Cylinder && !((s.b - s.a).norm() > 0))
    throw bad("the cylinder's axis has zero length");
}

double source_size(const std::vector<SizeSource>& sources, const Vec3& x, double h_max, double log_beta) {
  double h = kNoLimit;
  for (const SizeSource& s : sources) h = std::min(h, s.size_at(x, h_max, log_beta));
  return h;
}

std::vector<double> source_sizes(const std::vector<SizeSource>& sources, const std::vector<Vec3>& points,
                                 double h_max, double log_beta) {
  std::vector<double> h(points.size(), kNoLimit);
  if (sources.empty()) return h;
  for (size_t i = 0; i < points.size(); ++i) h[i] = source_size(sources, points[i], h_max, log_beta);
  return h;
}

}  // namespace sizemesh
