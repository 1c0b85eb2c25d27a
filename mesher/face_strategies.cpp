// One face's inside meshed from its boundary: the front's strategies in turn, leftovers closed by ears.
#include "mesher/face_strategies.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "core/predicates.h"
#include "core/stopwatch.h"
#include "mesher/advancing_front.h"
#include "mesher/face_boundary.h"
#include "mesher/fill_front.h"
#include "mesher/mesh_surface.h"
#include "mesher/optimise.h"

namespace sizemesh {
namespace mesh_surface_detail {
namespace {

// Leftover fronts closed by ear clipping: small ones after any strategy,
// larger ones only to avoid a hole after the last.
constexpr int kSmallLeftover = 64;
constexpr int kLargeLeftover = 5000;
// Strips closed across (fill_narrow): ear clipping is cubic in the edges.
constexpr int kNarrowLeftover = 400;

// A strip narrower than the elements (its whole boundary, or what a front
// left of it) closed by ears across it that face the surface at their
// centroids: a rounded edge's strip turns its normal round, so no chord
// faces both sides' normals and the front finds no valid triangle. Taken
// only when every new triangle spans the strip at under tan(12 deg) of the
// wanted size (no mesh of the strip can do better) or has no angle under 30
// degrees: ears across a strip a few elements wide are all about 12 degrees,
// and the front does better there. Otherwise fm is left as it was.
bool fill_narrow(FaceMesh& fm, const FaceSurface& fs, const std::vector<std::array<int, 2>>& open_edges) {
  if (static_cast<int>(open_edges.size()) > kNarrowLeftover) return false;  // before copying a large face
  FaceMesh filled = fm;
  if (!fill_front(filled, fs, open_edges, EarTest::kCentroid, kNarrowLeftover)) return false;
  for (size_t t = fm.tris.size(); t < filled.tris.size(); ++t) {
    const auto& tr = filled.tris[t];
    const Vec3 &a = filled.s[tr[0]].p, &b = filled.s[tr[1]].p, &c = filled.s[tr[2]].p;
    if (min_angle_deg(a, b, c) >= 30) continue;
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double h = std::min({filled.s[tr[0]].h, filled.s[tr[1]].h, filled.s[tr[2]].h});
    if (!(longest > 0) || !((b - a).cross(c - a).norm() / longest < kSliverTan * h)) return false;
  }
  fm = std::move(filled);
  return true;
}

// The region fm bounds is a strip narrower than the elements: its area over
// half its perimeter (the mean width of a strip) is under tan(12 deg) of the
// largest wanted size on its boundary. The area is the uv area of the loops
// times the mean area element |du x dv| at their nodes: a screen that keeps
// the ear clipping (cubic in the nodes) off faces it cannot close across.
bool narrow_region(const FaceMesh& fm) {
  if (fm.num_nodes() > kNarrowLeftover || fm.loops.empty()) return false;
  double uv_area = 0, perimeter = 0, element = 0, h = 0;
  int count = 0;
  for (const auto& loop : fm.loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      uv_area += 0.5 * (fm.uv[a].x() * fm.uv[b].y() - fm.uv[b].x() * fm.uv[a].y());
      perimeter += (fm.s[b].p - fm.s[a].p).norm();
      element += fm.s[a].du.cross(fm.s[a].dv).norm();
      h = std::max(h, fm.s[a].h);
      ++count;
    }
  if (!(count > 0) || !(perimeter > 0) || !(uv_area > 0)) return false;
  const double area = uv_area * element / count;
  return 2 * area / perimeter < kSliverTan * h;
}

// Every edge of fm's boundary loops, as a front to close.
std::vector<std::array<int, 2>> boundary_front(const FaceMesh& fm) {
  std::vector<std::array<int, 2>> out;
  for (const auto& loop : fm.loops)
    for (size_t i = 0; i < loop.size(); ++i) out.push_back({loop[i], loop[(i + 1) % loop.size()]});
  return out;
}

// Some triangle of fm turned against the surface at its uv centroid, or of
// zero area in space.
bool any_turned(const FaceMesh& fm, const FaceSurface& fs) {
  for (const auto& t : fm.tris) {
    const Vec3 &a = fm.s[t[0]].p, &b = fm.s[t[1]].p, &c = fm.s[t[2]].p;
    if (fs.turned_at_centroid(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]], (b - a).cross(c - a))) return true;
  }
  return false;
}

// Triangles of fm whose smallest angle in space is under 12 degrees.
int slivers(const FaceMesh& fm) {
  int n = 0;
  for (const auto& t : fm.tris) n += min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p) < kSliverDeg;
  return n;
}

// The inside of a face from its boundary `given` (mesher uv): the front's
// strategies, then the optimiser. Throws the kernel's Error.
void mesh_inside(const FaceMesh& given, FaceSurface& fs, const MeshOptions& o, FaceResult& r) {
  const int face = fs.face();
  Stopwatch clock;
  const Geometry& g = fs.geometry();
  long long evaluated = g.thread_surface_evaluations();
  auto evaluations = [&] {
    const long long now = g.thread_surface_evaluations(), d = now - evaluated;
    evaluated = now;
    return d;
  };
  const FaceMesh raw = off_bands(given, fs);
  FaceMesh steady = raw;
  const bool curled = steady_boundary_normals(steady, fs) > 0;
  const long long budget = front_step_budget(o.expected(face), raw.num_nodes());
  // Strict runs first: no triangle turned against the surface, leftovers
  // closed only by ears that face the surface; with the boundary normals
  // steadied where the surface curls, then (if that changed any) without.
  // If both leave a hole, a lenient run of the strategies whose loosest
  // levels it changes (2 and 3), its leftovers closed by facing ears where
  // they can be: a few inverted triangles rather than a hole.
  struct Attempt {
    const FaceMesh* boundary;
    bool lenient;
  };
  std::vector<Attempt> attempts = {{&steady, false}};
  if (curled) attempts.push_back({&raw, false});
  attempts.push_back({&steady, true});
  SplitBounds bounds;
  const AccuracyRules& rules = fs.size_field().accuracy();
  bounds.deviation = rules.deviation;
  bounds.max_turn = rules.turn(face);
  bounds.h_floor = rules.h_min;
  bool optimised = false;
  FrontResult fr;
  auto fill = [&](bool lenient, int max_edges) {
    return fill_front(r.mesh, fs, fr.open_edges, EarTest::kFacing, max_edges) ||
           (lenient && fill_front(r.mesh, fs, fr.open_edges, EarTest::kAny, max_edges));
  };
  // A strip too narrow for any point inside it (a rounded edge far below
  // the elements): closed across first; a front would fill it with points
  // of its own and every triangle at them a sliver.
  if (narrow_region(steady)) {
    r.mesh = steady;
    if (fill_narrow(r.mesh, fs, boundary_front(steady))) {
      fr.ok = true;
      r.filled = true;
    }
  }
  for (const Attempt& a : attempts) {
    if (fr.ok) break;
    for (int strategy = a.lenient ? 2 : 0; strategy < kStrategyCount && !fr.ok; ++strategy) {
      r.mesh = *a.boundary;
      fr = advancing_front(r.mesh, fs, strategy, budget, a.lenient);
      r.front_steps += fr.steps;
      r.front_work += fr.work;
      r.fronts_3d += fr.fronts_3d;
      r.strategy = strategy;
      // A few edges the front could not advance from: close them in place.
      if (!fr.ok && fill(a.lenient, kSmallLeftover)) {
        fr.ok = true;
        r.filled = true;
      }
      // A few edges left that no facing ear closes (a leftover loop the
      // front left turned in space): closed by any ears valid in uv and
      // optimised, kept when no triangle is then turned against the surface
      // at its centroid (the quality report's inverted triangle) and none is
      // under 12 degrees (else the other strategies may do better). What the
      // lenient run does last, without every other strategy run first.
      if (!fr.ok && !a.lenient && static_cast<int>(fr.open_edges.size()) <= kSmallLeftover) {
        FaceMesh untangled = r.mesh;
        if (fill_front(untangled, fs, fr.open_edges, EarTest::kAny, kSmallLeftover)) {
          optimise(untangled, fs, o.optimise_passes, bounds);
          if (!any_turned(untangled, fs) && slivers(untangled) == 0) {
            r.mesh = std::move(untangled);
            fr.ok = true;
            r.filled = true;
            optimised = true;
          }
        }
      }
      // Before the strategies that add points freely: a strip too narrow
      // for any point inside it is closed across.
      if (!fr.ok && !a.lenient && strategy == 1 && fill_narrow(r.mesh, fs, fr.open_edges)) {
        fr.ok = true;
        r.filled = true;
      }
    }
    // Before a hole: close the last strategy's leftover with ears.
    if (!fr.ok && fill(a.lenient, kLargeLeftover)) {
      fr.ok = true;
      r.filled = true;
    }
    r.lenient = a.lenient;
    if (fr.ok) break;
  }
  r.seconds_front = clock.lap();
  r.evaluations_front += evaluations();
  if (!fr.ok) {
    r.reason = fr.reason;
  } else {
    if (!optimised) optimise(r.mesh, fs, o.optimise_passes, bounds);
    r.seconds_optimise = clock.lap();
    r.evaluations_optimise += evaluations();
    for (Vec2& uv : r.mesh.uv) uv = fs.to_surface(uv);  // the mesh leaves in the surface's uv
    r.ok = true;
  }
}

}  // namespace

FaceResult mesh_face(const Geometry& g, const SizeField& h, const CurveMesh& cm, int face,
                     const MeshOptions& o) {
  FaceResult r;
  const long long start = g.thread_surface_evaluations();
  FaceSurface fs(g, h, face);
  try {
    FaceMesh boundary = face_boundary(g, cm, fs);
    r.evaluations_setup = g.thread_surface_evaluations() - start;
    mesh_inside(boundary, fs, o, r);
  } catch (const Error& e) {  // the kernel cannot evaluate the face, or its boundary is unusable
    r.reason = std::string("exception: ") + e.what();
  } catch (const std::bad_alloc&) {  // this face alone asked for too much: the others are kept
    r.reason = "out of memory while meshing this face";
  }  // anything else is a bug: it ends the run with its message rather than pass as a failed face
  r.size_queries = fs.size_queries;
  if (!r.ok) r.mesh = FaceMesh();
  return r;
}

}  // namespace mesh_surface_detail

using mesh_surface_detail::FaceResult;
using mesh_surface_detail::mesh_inside;

bool mesh_within(const Geometry& g, const SizeField& h, FaceMesh& fm, const MeshOptions& o, std::string& reason) {
  FaceResult r;
  FaceSurface fs(g, h, fm.face);
  try {
    FaceMesh raw;
    raw.face = fm.face;
    for (int i = 0; i < fm.num_nodes(); ++i) {
      const Vec2 uv = fs.to_mesher(fm.uv[i]);
      raw.add_node(uv, fs.eval(uv), fm.global[i]);
      raw.shared_xyz.back() = fm.shared_xyz[i];
    }
    raw.loops = fm.loops;
    mesh_inside(raw, fs, o, r);
  } catch (const Error& e) {
    r.reason = std::string("exception: ") + e.what();
  } catch (const std::bad_alloc&) {
    r.reason = "out of memory while meshing this face";
  }
  reason = r.reason;
  if (r.ok) fm = std::move(r.mesh);
  return r.ok;
}

}  // namespace sizemesh
