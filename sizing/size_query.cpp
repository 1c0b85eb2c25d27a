// The size query service (paper 4.2): faces checked, uv wrapped, the walk started; at() and at_xyz().
//
// The query answers with a walk-through base-element search in a face's uv
// space after Shan et al. 2008 (size_query_walk.cpp), linear interpolation in
// the base triangle (size_query_interpolate.h), boundary clamping and going
// around obstacles (size_query_boundary.cpp), and a 3D nearest-triangle query
// for at_xyz. Construction is in size_query_build.cpp, the counters in
// size_query_stats.cpp.
#include "sizing/size_query.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/triangle_bvh.h"
#include "sizing/size_query_face.h"

namespace sizemesh {

using size_query_detail::build_face;
using size_query_detail::kOwnedSlots;

namespace {

// Wraps x by period P to the position nearest the range [lo, hi].
double wrap_periodic(double x, double lo, double hi, double P) {
  double y = lo + std::fmod(x - lo, P);
  if (y < lo) y += P;
  const double above = y > hi ? y - hi : 0.0;
  const double below = lo - (y - P);
  return below < above ? y - P : y;
}

[[noreturn]] void throw_bad_face(int face, int num_faces) {
  throw Error("size query: face " + std::to_string(face) + " does not exist (the background mesh has " +
              std::to_string(num_faces) + " faces)");
}

[[noreturn]] void throw_empty_face(int face) {
  throw Error("size query: face " + std::to_string(face) +
              " has no background triangles, so no size can be looked up in its uv space");
}

[[noreturn]] void throw_bad_uv(int face) {
  throw Error("size query: a non-finite uv was asked on face " + std::to_string(face));
}

}  // namespace

SizeQuery::SizeQuery(const BackgroundMesh& bg, std::vector<double> h, std::vector<double> period_u,
                     std::vector<double> period_v)
    : bvh_(std::make_unique<TriangleBVH>(bg.xyz, bg.tris)), slots_(std::make_unique<StatSlot[]>(kOwnedSlots + 1)) {
  if (h.size() != bg.xyz.size())
    throw Error("size query: " + std::to_string(h.size()) + " sizes given for " + std::to_string(bg.xyz.size()) +
                " background vertices");
  const int nf = static_cast<int>(bg.patches.size());
  faces_.reserve(nf);
  for (int i = 0; i < nf; ++i) {
    const double pu = i < static_cast<int>(period_u.size()) ? period_u[i] : 0;
    const double pv = i < static_cast<int>(period_v.size()) ? period_v[i] : 0;
    faces_.push_back(build_face(bg.patches[i], i + 1, h, pu, pv));
  }
  tri_h_.resize(bg.tris.size());
  for (size_t t = 0; t < bg.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) tri_h_[t][k] = h[bg.tris[t][k]];
}

SizeQuery::~SizeQuery() = default;
SizeQuery::SizeQuery(SizeQuery&&) noexcept = default;
SizeQuery& SizeQuery::operator=(SizeQuery&&) noexcept = default;

int SizeQuery::num_faces() const { return static_cast<int>(faces_.size()); }

int SizeQuery::num_triangles(int face) const {
  if (face < 1 || face > num_faces()) return 0;
  return static_cast<int>(faces_[face - 1].tris.size());
}

const SizeQuery::Face& SizeQuery::face_data(int face) const {
  if (face < 1 || face > num_faces()) throw_bad_face(face, num_faces());
  const Face& f = faces_[face - 1];
  if (f.tris.empty()) throw_empty_face(face);
  return f;
}

// ---------------------------------------------------------------------------
// Queries in uv (paper 4.2)

SizeQuery::Hit SizeQuery::locate(int face, const Vec2& uv, int hint, QueryStats* stats) const {
  if (surface_ && face >= 1 && face <= num_faces() && faces_[face - 1].tris.empty()) {
    if (stats) ++stats->queries;
    return {at_xyz(surface_(face, uv)), -1};  // no uv triangulation to walk: the nearest size in space
  }
  const Face& f = face_data(face);
  if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) throw_bad_uv(face);
  // Periodic faces: bring the point into the patch's uv range (across the seam).
  Vec2 p = uv;
  if (f.period_u > 0 && (p.x() < f.lo.x() || p.x() > f.hi.x())) p.x() = wrap_periodic(p.x(), f.lo.x(), f.hi.x(), f.period_u);
  if (f.period_v > 0 && (p.y() < f.lo.y() || p.y() > f.hi.y())) p.y() = wrap_periodic(p.y(), f.lo.y(), f.hi.y(), f.period_v);
  // Start triangle: the hint, or the grid cell's triangle when nearer or no hint.
  const int i = static_cast<int>(std::clamp((p.x() - f.grid_lo.x()) * f.inv_du, 0.0, f.nx - 1.0));
  const int j = static_cast<int>(std::clamp((p.y() - f.grid_lo.y()) * f.inv_dv, 0.0, f.ny - 1.0));
  const int cell = f.cell_tri[static_cast<size_t>(j) * f.nx + i];
  int start = cell;
  if (static_cast<unsigned>(hint) < f.tris.size()) {
    start = hint;
    if (grid_with_hint_ && hint != cell) {
      // The nearer (uv distance to the centroid) of the hint and the cell's
      // triangle: a hint across a seam or several thin triangles away loses.
      const Tri &A = f.tris[hint], &B = f.tris[cell];
      const double da = (3 * p - A.uv[0] - A.uv[1] - A.uv[2]).squaredNorm();
      const double db = (3 * p - B.uv[0] - B.uv[1] - B.uv[2]).squaredNorm();
      if (db < da) start = cell;
    }
  }
  QueryStats st;
  st.queries = 1;
  const Hit hit = walk(f, p, start, st);
  st.max_visited = st.visited;
  if (stats) stats->add(st);
  return hit;
}

SizeQuery::Hit SizeQuery::locate_brute_force(int face, const Vec2& uv) const {
  const Face& f = face_data(face);
  if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) throw_bad_uv(face);
  Vec2 p = uv;
  if (f.period_u > 0 && (p.x() < f.lo.x() || p.x() > f.hi.x())) p.x() = wrap_periodic(p.x(), f.lo.x(), f.hi.x(), f.period_u);
  if (f.period_v > 0 && (p.y() < f.lo.y() || p.y() > f.hi.y())) p.y() = wrap_periodic(p.y(), f.lo.y(), f.hi.y(), f.period_v);
  QueryStats st;
  return brute_force(f, p, st);
}

double SizeQuery::at(int face, const Vec2& uv, int& hint) const {
  QueryStats st;
  const Hit hit = locate(face, uv, hint, &st);
  hint = hit.tri;
  count(st);
  return hit.h;
}

// ---------------------------------------------------------------------------
// Query in xyz: the size at the closest point of the nearest background triangle.

double SizeQuery::at_xyz(const Vec3& xyz) const {
  if (bvh_->size() == 0) throw Error("size query: the background mesh has no triangles");
  if (!xyz.allFinite()) throw Error("size query: a non-finite point was asked");
  const TriangleBVH::Closest c = bvh_->closest(xyz);
  const auto& h = tri_h_[c.tri];
  return c.weights[0] * h[0] + c.weights[1] * h[1] + c.weights[2] * h[2];
}

SizeQuery size_query_for(const Geometry& g, const BackgroundMesh& bg, std::vector<double> h) {
  std::vector<double> pu(g.num_faces()), pv(g.num_faces());
  for (int f = 1; f <= g.num_faces(); ++f) {
    pu[f - 1] = g.face_wrap_u(f);
    pv[f - 1] = g.face_wrap_v(f);
  }
  SizeQuery query(bg, std::move(h), std::move(pu), std::move(pv));
  query.set_surface([&g](int face, const Vec2& uv) { return g.eval_face(face, uv).p; });
  return query;
}

}  // namespace sizemesh
