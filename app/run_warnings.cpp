// The checks and warning lines of a run (app/run_warnings.h).
#include "app/run_warnings.h"

#include <iomanip>
#include <sstream>

#include "sizing/options.h"

namespace sizemesh {

void check_triangle_budget(const TriangleEstimate& e, double max_triangles, const SizeMap& h) {
  if (e.total <= max_triangles) return;
  std::string option = remedy(e.dominant());  // sizing/options.h
  if (option.empty()) option = "--farfield-h";  // the far field's element size, a flow-domain option
  std::ostringstream msg;
  msg << std::setprecision(3) << "the size map asks for about " << e.total << " triangles, more than "
      << flag_of("max_triangles") << " "
      << max_triangles << " (h_min " << h.h_min << ", h_max " << h.h_max << "); most come from sizes set by "
      << limit_name(e.dominant()) << ": raise " << option << ", or " << flag_of("max_triangles");
  throw Error(msg.str());
}

void warn_local_intersections(const MeshQuality& q, const WarningSink& warn) {
  if (q.local_self_intersections == 0) return;
  std::ostringstream msg;
  msg << q.local_self_intersections << " pairs of triangles intersect within a face or across a shared curve (faces";
  for (const auto& [a, b] : q.intersecting_faces) msg << " " << a << (a == b ? "" : "/" + std::to_string(b));
  msg << "): the CAD surfaces there likely cross";
  warn(msg.str());
}

void warn_crossings(const MeshQuality& q, const Preparation& p, const WarningSink& warn) {
  const long long n = q.self_intersections - q.local_self_intersections;
  if (n == 0 || !p.union_requested || !p.not_united.empty()) return;
  std::ostringstream msg;
  msg << n << " pairs of triangles of faces that share no curve intersect (faces";
  for (const auto& [a, b] : q.crossing_faces) msg << " " << a << "/" << b;
  msg << "): the united surface crosses itself there (exit 3)";
  warn(msg.str());
}

void warn_open(const MeshQuality& q, const Preparation& p, bool faces_failed, const WarningSink& warn) {
  if (q.boundary_edges + q.nonmanifold_edges == 0 || !closed_expected(p) || !p.not_united.empty() || faces_failed ||
      q.self_intersections > q.local_self_intersections)
    return;
  std::ostringstream msg;
  msg << "the united surface is not closed: " << q.boundary_edges << " boundary and " << q.nonmanifold_edges
      << " non-manifold edges (faces";
  for (int f : q.open_faces) msg << " " << f;
  msg << ") (exit 3)";
  warn(msg.str());
}

void measure_h_min(const SurfaceMesh& m, const std::vector<double>& target, const std::vector<double>& limited_by,
                   double h_min, RunReport& r) {
  double n = 0, area = 0, total = 0;
  auto asked = [&](int node) {
    if (limited_by.size() != target.size()) return false;
    const int l = static_cast<int>(limited_by[node]);
    return l == static_cast<int>(Limit::Aero) || l == static_cast<int>(Limit::Source) ||
           l == static_cast<int>(Limit::User);
  };
  for (const auto& t : m.tris) {
    const double a = 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
    total += a;
    const double mean = (target[t[0]] + target[t[1]] + target[t[2]]) / 3;
    if (mean <= 1.05 * h_min && mean >= 0.95 * h_min && !asked(t[0]) && !asked(t[1]) && !asked(t[2]))
      n += 1, area += a;
  }
  r.at_h_min_share = m.tris.empty() ? 0 : n / m.tris.size();
  r.at_h_min_area_share = total > 0 ? area / total : 0;
}

void warn_h_min(const RunReport& r, double h_min, const WarningSink& warn) {
  if (!(r.at_h_min_share > 0.05)) return;
  std::ostringstream msg;
  msg << std::setprecision(3) << 100 * r.at_h_min_share << "% of the triangles (" << 100 * r.at_h_min_area_share
      << "% of the area) are sized at h_min " << h_min
      << ": lower --h-min to resolve those regions, or raise it for fewer triangles";
  warn(msg.str());
}

void warn_faces_without_background(const BackgroundMesh& bg, const WarningSink& warn) {
  if (bg.faces_without_patch.empty()) return;
  std::ostringstream msg;
  msg << (bg.faces_without_patch.size() == 1 ? "face " : "faces ");
  for (size_t i = 0; i < bg.faces_without_patch.size() && i < 10; ++i)
    msg << (i ? ", " : "") << bg.faces_without_patch[i];
  if (bg.faces_without_patch.size() > 10) msg << " and " << bg.faces_without_patch.size() - 10 << " more";
  msg << (bg.faces_without_patch.size() == 1 ? " has" : " have")
      << " no background mesh (the B-rep tessellation failed there): their sizes are taken from the nearest other face";
  warn(msg.str());
}

void warn_not_united(const Preparation& p, const WarningSink& warn) {
  if (p.not_united.empty()) return;
  std::ostringstream msg;
  msg << (p.not_united.size() == 1 ? "component" : "components");
  for (size_t i = 0; i < p.not_united.size(); ++i) {
    const Component& c = p.components[p.not_united[i] - 1];
    msg << (i ? "; " : " ") << p.not_united[i] << " (" << c.faces << " faces, "
        << c.route.substr(c.route.find(':') == std::string::npos ? 0 : c.route.find(':') + 2) << ")";
  }
  msg << " could not be united with the rest: meshed where they lie, so the surface is not one closed body (exit 3)";
  warn(msg.str());
}

void warn_left_out(const std::vector<int>& ks, const char* one, const char* many, const char* why,
                   const WarningSink& warn) {
  if (ks.empty()) return;
  std::ostringstream msg;
  msg << (ks.size() == 1 ? "component" : "components");
  for (size_t i = 0; i < ks.size(); ++i) msg << (i ? ", " : " ") << ks[i];
  msg << (ks.size() == 1 ? one : many) << why << ": no wall, left out of the wetted surface";
  warn(msg.str());
}

}  // namespace sizemesh
