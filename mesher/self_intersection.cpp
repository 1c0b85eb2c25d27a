#include "mesher/self_intersection.h"

#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/predicates.h"
#include "core/triangle_bvh.h"

namespace sizemesh {

namespace {

// Triangles sharing only corner v: a line through v along one of their edges
// at v with one triangle strictly on each side (in s's projection) shows they
// meet only at v: a point of both would project into both. Sides are exact.
bool fan_neighbours_apart(const std::array<Vec3, 3>& cs, int is, const std::array<Vec3, 3>& ct, int it) {
  const DominantProjection flat(cs[0], cs[1], cs[2]);
  const Vec2 v = flat(cs[is]);
  const Vec2 s1 = flat(cs[(is + 1) % 3]), s2 = flat(cs[(is + 2) % 3]);
  const Vec2 t1 = flat(ct[(it + 1) % 3]), t2 = flat(ct[(it + 2) % 3]);
  auto separates = [&](const Vec2& e, const Vec2& own, const Vec2& o1, const Vec2& o2) {
    const int side = orient2d_sign(v, e, own);
    return side != 0 && orient2d_sign(v, e, o1) == -side && orient2d_sign(v, e, o2) == -side;
  };
  return separates(s1, s2, t1, t2) || separates(s2, s1, t1, t2) || separates(t1, t2, s1, s2) ||
         separates(t2, t1, s1, s2);
}

// Triangles s and t (node ids ns, nt; corners cs, ct) meet beyond their shared nodes.
bool pair_meets(const std::array<int, 3>& ns, const std::array<int, 3>& nt, const std::array<Vec3, 3>& cs,
                const std::array<Vec3, 3>& ct) {
  int shared = 0, is = -1, it = -1;  // corners of the (last) shared node
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ns[i] == nt[j]) {
        ++shared;
        is = i;
        it = j;
      }
  if (shared == 0) return triangles_meet(cs, ct);
  if (shared == 3) return true;
  if (shared == 1) {
    if (fan_neighbours_apart(cs, is, ct, it)) return false;
    // The edge opposite the shared node, of either triangle, meets the other.
    return segment_meets_triangle(cs[(is + 1) % 3], cs[(is + 2) % 3], ct[0], ct[1], ct[2]) ||
           segment_meets_triangle(ct[(it + 1) % 3], ct[(it + 2) % 3], cs[0], cs[1], cs[2]);
  }
  // A shared edge: the apexes are the corners not shared.
  int as = 0, at = 0;
  for (int i = 0; i < 3; ++i) {
    if (ns[i] != nt[0] && ns[i] != nt[1] && ns[i] != nt[2]) as = i;
    if (nt[i] != ns[0] && nt[i] != ns[1] && nt[i] != ns[2]) at = i;
  }
  const Vec3 &u = cs[(as + 1) % 3], &w = cs[(as + 2) % 3], &a = cs[as], &b = ct[at];
  // They overlap only when coplanar with the apexes on the same side of the
  // edge (sides in s's projection, exact where coplanar); the side test is
  // cheap and usually settles it before the coplanarity test.
  const DominantProjection flat(cs[0], cs[1], cs[2]);
  const int sa = orient2d_sign(flat(u), flat(w), flat(a)), sb = orient2d_sign(flat(u), flat(w), flat(b));
  if (sa == 0 || sa != sb) return false;
  return orient3d_sign(u, w, a, b) == 0;
}

}  // namespace

SelfIntersections find_self_intersections(const SurfaceMesh& m, size_t keep, const std::vector<char>* among) {
  SelfIntersections out;
  const int nt = static_cast<int>(m.tris.size());
  if (nt < 2) return out;
  const TriangleBVH bvh(m.xyz, m.tris);
  // Zero-area triangles are counted apart (quality report), not here.
  std::vector<char> flat(nt);
  tbb::parallel_for(0, nt, [&](int t) { flat[t] = zero_area(m.xyz[m.tris[t][0]], m.xyz[m.tris[t][1]], m.xyz[m.tris[t][2]]); });
  // Each thread keeps its `keep` smallest pairs (trimmed when twice that
  // many), so the pairs kept are the `keep` smallest of all, whichever
  // thread found them: callers that act on them (cut_faces.cpp) act alike
  // on every run.
  tbb::combinable<long long> count;
  tbb::enumerable_thread_specific<std::vector<std::array<int, 2>>> found;
  auto trim = [keep](std::vector<std::array<int, 2>>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(keep), v.end());
    v.resize(keep);
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, nt, 1024), [&](const tbb::blocked_range<int>& r) {
    long long& mine = count.local();
    auto& pairs = found.local();
    for (int s = r.begin(); s != r.end(); ++s) {
      const auto& cs = bvh.corners(s);
      if (flat[s] || (among && !(*among)[s])) continue;
      bvh.overlapping(bvh.box(s), [&](int t) {
        // Each pair once: t after s, or t not checked on its own.
        if (t == s || flat[t] || (t < s && !(among && !(*among)[t]))) return;
        if (!pair_meets(m.tris[s], m.tris[t], cs, bvh.corners(t))) return;
        ++mine;
        if (keep == 0) return;
        pairs.push_back({s, t});
        if (pairs.size() / 2 >= keep) trim(pairs);
      });
    }
  });
  out.pairs = count.combine([](long long a, long long b) { return a + b; });
  for (auto& pairs : found) out.kept.insert(out.kept.end(), pairs.begin(), pairs.end());
  if (out.kept.size() > keep) trim(out.kept);
  std::sort(out.kept.begin(), out.kept.end());
  return out;
}

}  // namespace sizemesh
