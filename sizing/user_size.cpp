#include "sizing/user_size.h"

#include <muParser.h>

#include <cmath>
#include <sstream>

#include "sizing/size_map.h"

namespace sizemesh {

namespace {

// Evaluates one prescribed size at vertices; compiles the expression once.
class SizeRule {
 public:
  SizeRule(const UserSize& s, const std::string& what) : s_(s), what_(what) {
    if (s.expression.empty()) return;
    parser_.DefineVar("x", &x_);
    parser_.DefineVar("y", &y_);
    parser_.DefineVar("z", &z_);
    try {
      parser_.SetExpr(s.expression);
      parser_.Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw Error("malformed size expression for " + what + " '" + s.expression + "': " + e.GetMsg());
    }
  }
  double at(const Vec3& p) {
    if (s_.expression.empty()) return s_.value;
    x_ = p.x();
    y_ = p.y();
    z_ = p.z();
    const double h = parser_.Eval();
    if (!(h > 0) || !std::isfinite(h)) {
      std::ostringstream m;
      m << "size expression for " << what_ << " '" << s_.expression << "' gives " << h << " at (" << p.x() << ", "
        << p.y() << ", " << p.z() << "); sizes must be positive";
      throw Error(m.str());
    }
    return h;
  }

 private:
  UserSize s_;
  std::string what_;
  mu::Parser parser_;
  double x_ = 0, y_ = 0, z_ = 0;
};

}  // namespace

std::vector<double> user_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p) {
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  auto apply = [&](SizeRule& rule, int v) { h[v] = std::min(h[v], rule.at(bg.xyz[v])); };
  for (const auto& [id, s] : p.point_size) {
    SizeRule rule(s, "point " + std::to_string(id));
    apply(rule, id - 1);
  }
  for (const auto& [id, s] : p.curve_size) {
    SizeRule rule(s, "curve " + std::to_string(id));
    for (int v = 0; v < bg.num_vertices(); ++v)
      if (bg.dim[v] == 1 && bg.entity[v] == id) apply(rule, v);
    for (int pt : {g.curve_start_point(id), g.curve_end_point(id)})
      if (pt > 0) apply(rule, pt - 1);
  }
  for (const auto& [id, s] : p.face_size) {
    SizeRule rule(s, "face " + std::to_string(id));
    for (int v : bg.patches[id - 1].vertex) apply(rule, v);
  }
  return h;
}

}  // namespace sizemesh
