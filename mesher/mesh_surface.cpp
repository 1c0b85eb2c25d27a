#include "mesher/mesh_surface.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <new>

#include <tbb/task_arena.h>
#include <tbb/parallel_for.h>

#include "geometry/predicates.h"
#include "geometry/stopwatch.h"
#include "mesher/advancing_front.h"
#include "mesher/discretise_curves.h"
#include "mesher/face_boundary.h"
#include "mesher/fill_front.h"
#include "mesher/optimise.h"

namespace sizemesh {
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

struct FaceResult {
  FaceMesh mesh;
  bool ok = false;
  std::string reason;
  long long size_queries = 0;
  int fronts_3d = 0;
  int strategy = 0;  // front strategy that closed the face
  long long front_steps = 0;
  bool filled = false;  // the front's leftover was closed by ear clipping
  bool lenient = false; // the strict run left a hole: meshed by the lenient one
  double seconds_front = 0, seconds_optimise = 0;
};

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
  const FaceMesh raw = off_bands(given, fs);
  FaceMesh steady = raw;
  const bool curled = steady_boundary_normals(steady, fs) > 0;
  const double expected = face < static_cast<int>(o.expected_triangles.size()) ? o.expected_triangles[face] : 0.0;
  const long long budget = front_step_budget(expected, raw.num_nodes());
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
  bounds.deviation = o.deviation;
  bounds.max_turn = face < static_cast<int>(o.max_turn.size()) ? o.max_turn[face] : 0.0;
  bounds.h_floor = o.h_min;
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
  if (!fr.ok) {
    r.reason = fr.reason;
  } else {
    if (!optimised) optimise(r.mesh, fs, o.optimise_passes, bounds);
    r.seconds_optimise = clock.lap();
    for (Vec2& uv : r.mesh.uv) uv = fs.to_surface(uv);  // the mesh leaves in the surface's uv
    r.ok = true;
  }
}

// One face, start to end; a face the geometry cannot mesh is returned with its
// reason, not thrown (only a bug escapes).
FaceResult mesh_face(const Geometry& g, const SizeFunction& h, const CurveMesh& cm, int face,
                     const MeshOptions& o) {
  FaceResult r;
  FaceSurface fs(g, h, face);
  try {
    mesh_inside(face_boundary(g, cm, fs), fs, o, r);
  } catch (const Error& e) {  // the kernel cannot evaluate the face, or its boundary is unusable
    r.reason = std::string("exception: ") + e.what();
  } catch (const std::bad_alloc&) {  // this face alone asked for too much: the others are kept
    r.reason = "out of memory while meshing this face";
  }  // anything else is a bug: it ends the run with its message rather than pass as a failed face
  r.size_queries = fs.size_queries;
  if (!r.ok) r.mesh = FaceMesh();
  return r;
}

// The stages, in the arena mesh_surface() sets up.
SurfaceMesh mesh_in_arena(const Geometry& g, const SizeFunction& h, const MeshOptions& o) {
  SurfaceMesh out;
  // 1. Curves: one unit mesh per curve (paper 2.1), shared by its faces.
  Stopwatch clock;
  CurveMesh cm;
  try {
    cm = discretise_curves(g, h, o.deviation);
  } catch (const Error&) {  // nothing can be meshed without the curves
    for (int f = 1; f <= g.num_faces(); ++f)
      out.failures.push_back({f, "the curves could not be discretised (geometry kernel error)"});
    return out;
  }
  out.stats.seconds_curves = clock.lap();
  out.stats.size_queries += cm.size_queries;

  // 2. Faces: independent once the curves are fixed.
  const int nf = g.num_faces();
  std::vector<FaceResult> faces(nf + 1);
  std::atomic<int> done{0};
  tbb::parallel_for(1, nf + 1, [&](int f) {
    faces[f] = mesh_face(g, h, cm, f, o);
    if (o.on_face_done) o.on_face_done(++done, nf);
  });
  out.stats.seconds_faces = clock.lap();

  // 3. Assembly in face order: shared nodes by index, inner nodes appended.
  out.xyz = std::move(cm.xyz);
  out.node_dim = std::move(cm.node_dim);
  out.node_entity = std::move(cm.node_entity);
  for (int f = 1; f <= nf; ++f) {
    FaceResult& r = faces[f];
    out.stats.size_queries += r.size_queries;
    out.stats.fronts_3d += r.fronts_3d;
    out.stats.front_steps += r.front_steps;
    out.stats.faces_retried += r.strategy > 0;
    out.stats.faces_relaxed += r.strategy >= 2;
    out.stats.faces_lenient += r.lenient;
    out.stats.faces_filled += r.filled;
    out.stats.seconds_front += r.seconds_front;
    out.stats.seconds_optimise += r.seconds_optimise;
    if (!r.ok) {
      out.failures.push_back({f, r.reason});
      continue;
    }
    const FaceMesh& fm = r.mesh;
    std::vector<int> id(fm.num_nodes(), -1);
    for (int i = 0; i < fm.num_nodes(); ++i) {
      if (fm.global[i] >= 0) {
        id[i] = fm.global[i];
        continue;
      }
      id[i] = static_cast<int>(out.xyz.size());
      out.xyz.push_back(fm.s[i].p);
      out.node_dim.push_back(2);
      out.node_entity.push_back(f);
    }
    const bool flip = g.face_reversed(f);
    for (const auto& t : fm.tris) {
      if (fm.pole_triangle(t)) continue;  // zero area on a pole
      std::array<int, 3> gt{id[t[0]], id[t[1]], id[t[2]]};
      std::array<Vec2, 3> uv{fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]};
      if (flip) {
        std::swap(gt[1], gt[2]);
        std::swap(uv[1], uv[2]);
      }
      out.tris.push_back(gt);
      out.tri_face.push_back(f);
      out.tri_uv.push_back(uv);
    }
  }
  drop_back_to_back(out);
  flip_shared_inner_edges(out);
  return out;
}

}  // namespace

void drop_back_to_back(SurfaceMesh& m) {
  std::map<std::array<int, 3>, std::vector<int>> by_nodes;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    std::array<int, 3> key = m.tris[t];
    std::sort(key.begin(), key.end());
    by_nodes[key].push_back(static_cast<int>(t));
  }
  // Opposite orientation: b's cyclic order is a's reversed.
  auto opposite = [&](int a, int b) {
    const auto &x = m.tris[a], &y = m.tris[b];
    for (int k = 0; k < 3; ++k)
      if (y[k] == x[0]) return y[(k + 1) % 3] == x[2];
    return false;
  };
  std::vector<char> drop(m.tris.size(), 0);
  for (const auto& [key, list] : by_nodes)
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size() && !drop[list[i]]; ++j)
        if (!drop[list[j]] && opposite(list[i], list[j])) drop[list[i]] = drop[list[j]] = 1;
  size_t kept = 0;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    if (drop[t]) continue;
    m.tris[kept] = m.tris[t];
    m.tri_face[kept] = m.tri_face[t];
    m.tri_uv[kept] = m.tri_uv[t];
    ++kept;
  }
  m.stats.back_to_back_dropped = static_cast<int>(m.tris.size() - kept);
  m.tris.resize(kept);
  m.tri_face.resize(kept);
  m.tri_uv.resize(kept);
}

void flip_shared_inner_edges(SurfaceMesh& m) {
  // Edge (a < b) -> triangles using it.
  std::map<std::pair<int, int>, std::vector<int>> uses;
  for (size_t t = 0; t < m.tris.size(); ++t)
    for (int k = 0; k < 3; ++k)
      uses[std::minmax(m.tris[t][k], m.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
  auto normal = [&](const std::array<int, 3>& t) {
    return (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]);
  };
  int flipped = 0;
  for (const auto& [e, list] : uses) {
    if (list.size() != 4) continue;
    // Two faces, two triangles each: flip the edge inside the first face
    // whose quad allows it.
    std::map<int, std::vector<int>> by_face;
    for (int t : list) by_face[m.tri_face[t]].push_back(t);
    if (by_face.size() != 2) continue;
    for (auto& [f, pair] : by_face) {
      if (pair.size() != 2) break;
      const int t1 = pair[0], t2 = pair[1];
      // t1 = (a, b, c) with a -> b along the edge; t2 holds b -> a and d.
      int k1 = 0;
      while (std::pair<int, int>(std::minmax(m.tris[t1][k1], m.tris[t1][(k1 + 1) % 3])) != e) ++k1;
      const int a = m.tris[t1][k1], b = m.tris[t1][(k1 + 1) % 3], c = m.tris[t1][(k1 + 2) % 3];
      int k2 = 0;
      while (m.tris[t2][k2] != b) ++k2;
      if (m.tris[t2][(k2 + 1) % 3] != a) break;  // not opposite: leave it
      const int d = m.tris[t2][(k2 + 2) % 3];
      if (c == d || uses.count(std::pair<int, int>(std::minmax(c, d)))) break;
      auto uv_of = [&](int t, int n) {
        for (int k = 0; k < 3; ++k)
          if (m.tris[t][k] == n) return m.tri_uv[t][k];
        return Vec2(0, 0);
      };
      const std::array<int, 3> n1 = {a, d, c}, n2 = {d, b, c};
      const Vec3 before = normal(m.tris[t1]) + normal(m.tris[t2]);
      if (!(normal(n1).dot(before) > 0 && normal(n2).dot(before) > 0)) continue;
      const std::array<Vec2, 3> uv1 = {uv_of(t1, a), uv_of(t2, d), uv_of(t1, c)};
      const std::array<Vec2, 3> uv2 = {uv_of(t2, d), uv_of(t1, b), uv_of(t1, c)};
      m.tris[t1] = n1, m.tri_uv[t1] = uv1;
      m.tris[t2] = n2, m.tri_uv[t2] = uv2;
      ++flipped;
      break;
    }
  }
  m.stats.shared_edges_flipped = flipped;
}

SurfaceMesh mesh_surface(const Geometry& g, const SizeFunction& h, const MeshOptions& o) {
  // A local arena: the thread count applies to this call only.
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  SurfaceMesh out;
  arena.execute([&] { out = mesh_in_arena(g, h, o); });
  return out;
}

bool mesh_within(const Geometry& g, const SizeFunction& h, FaceMesh& fm, const MeshOptions& o, std::string& reason) {
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

void set_accuracy(MeshOptions& o, const SizingParams& p, double h_min, int faces) {
  o.deviation = p.deviation;
  o.h_min = h_min;
  o.max_turn.assign(faces + 1, 0.0);
  o.size_slope.assign(faces + 1, 0.0);
  for (int f = 1; f <= faces; ++f) {
    o.max_turn[f] = p.face_phi_c(f) * kPi / 180.0;
    const auto beta = p.face_beta.find(f);
    o.size_slope[f] = std::log(beta == p.face_beta.end() ? p.beta : beta->second);
  }
}

}  // namespace sizemesh
