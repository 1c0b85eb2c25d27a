// The faces a mesh-level union cut, meshed again in rounds until no new triangle opens an edge or crosses another.
#include "mesher/cut_faces.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "background/background_mesh.h"
#include "mesher/curve_node_spacing.h"
#include "mesher/cut_face_regions.h"
#include "mesher/junction_chains.h"
#include "mesher/junction_nodes.h"
#include "mesher/junction_size.h"
#include "mesher/junction_slivers.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "mesher/self_intersection.h"

namespace sizemesh {
namespace {

constexpr int kRounds = 5;

}  // namespace

using namespace cut_faces_detail;  // the remesh's steps

CutFacesResult remesh_cut_faces(SurfaceMesh& s, const Geometry& g, const SizeField& h, const MeshOptions& o,
                                MeshUnionResult& u) {
  CutFacesResult out;
  std::vector<std::array<int, 2>> junction = u.junction;
  if (junction.empty()) return out;
  Eigen::AlignedBox3d box;
  for (const Vec3& x : s.xyz) box.extend(x);
  const double tol = 1e-13 * (box.isEmpty() ? 1.0 : box.diagonal().norm());
  bool merged = merge_coincident(s, junction, 1e3 * tol);
  merged = space_curve_nodes(s, g, h, h.accuracy().size_slope, junction) || merged;
  const Topology topo(s, g, junction);
  std::vector<Chain> chains = junction_chains(s, topo);
  std::vector<Vec3> xyz = s.xyz;
  JunctionGradedSize graded(g, h, h.accuracy().size_slope);
  for (Chain& c : chains) {
    if (c.nodes.size() < 2) continue;
    resample(c, s, topo, g, h, tol);
    for (const Vec3& x : c.x) {
      c.id.push_back(static_cast<int>(xyz.size()));
      xyz.push_back(x);
    }
    for (size_t i = 0; i < c.size.size(); ++i)
      for (int f : {c.fa, c.fb}) graded.add(f, s.xyz[c.nodes[i]], c.size[i]);
  }
  graded.finish();
  // The faces on either side of a junction, and those the union's band
  // remesh reached: its uniform length splits the CAD curves it crosses, and
  // a face beyond them is left with fans of slivers on each split edge.
  std::set<int> cut = u.band_faces;
  for (const Chain& c : chains)
    for (size_t j = 0; j + 1 < c.nodes.size(); ++j)
      for (int t : topo.edge_tris.at(edge_key(c.nodes[j], c.nodes[j + 1]))) cut.insert(s.tri_face[t]);
  std::map<int, std::vector<int>> tris_of;
  for (size_t t = 0; t < s.tris.size(); ++t)
    if (cut.count(s.tri_face[t])) tris_of[s.tri_face[t]].push_back(static_cast<int>(t));

  const size_t open_before = open_edges(s);
  // More crossing pairs than s had before its faces were meshed again. The
  // union counted the pairs of the mesh it made; a merge or a spaced curve
  // may change that, so s is counted again (once) when a round's result has
  // more than the union's count.
  long long crossing_before = !merged && u.crossing_pairs >= 0 ? u.crossing_pairs : -1;
  auto more_crossings = [&](long long pairs) {
    if (crossing_before < 0 && u.crossing_pairs >= 0 && pairs <= u.crossing_pairs) return false;
    if (crossing_before < 0) crossing_before = find_self_intersections(s, 0).pairs;
    return pairs > crossing_before;
  };
  std::set<int> kept;        // faces left with their triangles
  std::set<size_t> frozen;   // chains that keep their nodes
  std::set<int> held;        // triangles of faces meshed again that stay, with their nodes
  std::map<int, std::vector<Eigen::AlignedBox3d>> old_boxes;  // by face, of tris_of's triangles
  // Regions meshed in an earlier round, by face: the boundary given and the
  // mesh made. A round meshes again only the regions whose boundary changed
  // (those next to a face that now keeps its triangles).
  std::map<int, std::vector<std::pair<FaceMesh, FaceMesh>>> meshed_before;
  for (int round = 0; round < kRounds; ++round) {
    // Chains substituted: both faces meshed again. A face whose boundary
    // cannot be walked keeps its triangles; that changes which chains are
    // substituted, so until nothing changes.
    std::vector<int> owner(xyz.size(), -1);
    std::unordered_map<uint64_t, int> chain_of_edge;
    std::map<int, std::vector<Region>> regions;
    for (bool changed = true; changed;) {
      changed = false;
      std::fill(owner.begin(), owner.end(), -1);
      chain_of_edge.clear();
      for (size_t k = 0; k < chains.size(); ++k) {
        const Chain& c = chains[k];
        if (!c.usable || frozen.count(k) || kept.count(c.fa) || kept.count(c.fb)) continue;
        for (size_t j = 0; j + 1 < c.nodes.size(); ++j) chain_of_edge[edge_key(c.nodes[j], c.nodes[j + 1])] = k;
        for (size_t j = 1; j + 1 < c.nodes.size(); ++j) owner[c.nodes[j]] = static_cast<int>(k);
      }
      regions.clear();
      for (const auto& [f, all_tris] : tris_of) {
        if (kept.count(f)) continue;
        std::vector<int> tris;
        for (int t : all_tris)
          if (!held.count(t)) tris.push_back(t);
        bool ok = false;
        auto r = face_regions(s, g, f, tris, chains, owner, chain_of_edge, ok);
        if (!ok && held_pinches(s, all_tris, tris, held)) {
          changed = true;
          break;
        }
        if (!ok) {
          // First with its junctions' old nodes, then as it is.
          bool froze = false;
          for (size_t k = 0; k < chains.size(); ++k)
            if ((chains[k].fa == f || chains[k].fb == f) && chains[k].usable) froze = frozen.insert(k).second || froze;
          if (!froze) kept.insert(f);
          changed = true;
          break;
        }
        regions[f] = std::move(r);
      }
    }
    // Every region meshed (in parallel: faces are independent).
    std::vector<Region*> all;
    for (auto& [f, list] : regions)
      for (Region& r : list) all.push_back(&r);
    std::vector<char> meshed(all.size(), 0);
    std::vector<const FaceMesh*> earlier(all.size(), nullptr);
    for (size_t i = 0; i < all.size(); ++i)
      for (const auto& [given, made] : meshed_before[all[i]->boundary.face])
        if (same_boundary(given, all[i]->boundary)) earlier[i] = &made;
    std::vector<FaceMesh> given(all.size());
    tbb::parallel_for(size_t(0), all.size(), [&](size_t i) {
      if (earlier[i]) {
        all[i]->boundary = *earlier[i];
        meshed[i] = 1;
        return;
      }
      given[i] = all[i]->boundary;
      std::string why;
      meshed[i] = mesh_within(g, graded, all[i]->boundary, o, why);
      // A front that cannot close a region at the graded sizes (a junction
      // that hooks back on a face with a stretched parametrisation) may at
      // the size map's own.
      if (!meshed[i]) {
        all[i]->boundary = given[i];
        meshed[i] = mesh_within(g, h, all[i]->boundary, o, why);
      }
    });
    for (size_t i = 0; i < all.size(); ++i)
      if (meshed[i] && !earlier[i]) meshed_before[all[i]->boundary.face].emplace_back(std::move(given[i]), all[i]->boundary);
    bool failed = false;
    for (size_t i = 0; i < all.size(); ++i)
      if (!meshed[i]) kept.insert(all[i]->boundary.face), failed = true;
    if (failed) continue;

    // The new mesh: the faces meshed again replace their triangles.
    SurfaceMesh r;
    r.failures = s.failures;
    r.stats = s.stats;
    r.xyz = xyz;
    r.node_dim = s.node_dim;
    r.node_entity = s.node_entity;
    for (const Chain& c : chains)
      for (size_t j = 0; j < c.id.size(); ++j) {
        r.node_dim.push_back(2);
        r.node_entity.push_back(std::min(c.fa, c.fb));
      }
    std::vector<std::array<int, 3>> tris;
    std::vector<int> tri_face, fresh;
    std::vector<std::array<Vec2, 3>> tri_uv;
    for (size_t t = 0; t < s.tris.size(); ++t)
      if (!regions.count(s.tri_face[t]) || held.count(static_cast<int>(t))) {
        tris.push_back(s.tris[t]);
        tri_face.push_back(s.tri_face[t]);
        tri_uv.push_back(s.tri_uv[t]);
      }
    for (const auto& [f, list] : regions)
      for (const Region& reg : list) {
        const FaceMesh& fm = reg.boundary;
        std::vector<int> id(fm.num_nodes());
        for (int i = 0; i < fm.num_nodes(); ++i) {
          if (fm.global[i] >= 0) {
            id[i] = fm.global[i];
            continue;
          }
          id[i] = static_cast<int>(r.xyz.size());
          r.xyz.push_back(fm.s[i].p);
          r.node_dim.push_back(2);
          r.node_entity.push_back(f);
        }
        for (const auto& t : fm.tris) {
          std::array<int, 3> gt{id[t[0]], id[t[1]], id[t[2]]};
          std::array<Vec2, 3> uv{fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]};
          if (gt[0] == gt[1] || gt[1] == gt[2] || gt[0] == gt[2]) continue;  // on a pole
          if (reg.flip) std::swap(gt[1], gt[2]), std::swap(uv[1], uv[2]);
          fresh.push_back(static_cast<int>(tris.size()));
          tris.push_back(gt);
          tri_face.push_back(f);
          tri_uv.push_back(uv);
        }
      }
    // Triangles by face, in their order; unused nodes dropped, the others in their order.
    std::vector<int> order(tris.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return tri_face[a] < tri_face[b]; });
    std::vector<int> used(r.xyz.size(), -1);
    for (const auto& t : tris)
      for (int n : t) used[n] = 0;
    SurfaceMesh m;
    m.failures = r.failures;
    m.stats = r.stats;
    for (size_t n = 0; n < used.size(); ++n)
      if (used[n] == 0) {
        used[n] = static_cast<int>(m.xyz.size());
        m.xyz.push_back(r.xyz[n]);
        m.node_dim.push_back(r.node_dim[n]);
        m.node_entity.push_back(r.node_entity[n]);
      }
    std::vector<char> is_fresh(tris.size(), 0);
    for (int t : fresh) is_fresh[t] = 1;
    std::vector<char> fresh_sorted;
    for (int t : order) {
      m.tris.push_back({used[tris[t][0]], used[tris[t][1]], used[tris[t][2]]});
      m.tri_face.push_back(tri_face[t]);
      m.tri_uv.push_back(tri_uv[t]);
      fresh_sorted.push_back(is_fresh[t]);
    }
    // Two faces meshed again on either side of a thin corner may both join
    // the same two curve nodes by an inner edge (an edge used four times).
    size_t open_now = open_edges(m);
    if (open_now > open_before) {
      flip_shared_inner_edges(m);
      open_now = open_edges(m);
    }
    if (open_now > open_before) {
      // Faces whose new triangles leave an edge open or used more than twice
      // keep theirs next round.
      std::unordered_map<uint64_t, std::vector<int>> uses;
      for (size_t t = 0; t < m.tris.size(); ++t)
        for (int k = 0; k < 3; ++k) uses[edge_key(m.tris[t][k], m.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
      bool blamed = false;
      for (const auto& [e, u] : uses)
        if (u.size() != 2)
          for (int t : u)
            if (fresh_sorted[t]) blamed = kept.insert(m.tri_face[t]).second || blamed;
      if (!blamed) return out;
      continue;
    }
    // New triangles that cross others or turn against their surface.
    std::vector<int> wrong;
    const SelfIntersections hits = find_self_intersections(m, size_t(1) << 16);
    if (more_crossings(hits.pairs))
      for (const auto& [a, b] : hits.kept)
        for (int t : {a, b})
          if (fresh_sorted[t]) wrong.push_back(t);
    const size_t crossing_wrong = wrong.size();
    for (size_t t = 0; t < m.tris.size(); ++t)
      if (fresh_sorted[t] && inverted_triangle(m, g, t)) wrong.push_back(static_cast<int>(t));
    bool blamed = false;
    if (!wrong.empty()) {
      // Where two surfaces graze (a fin's root section lying on a fuselage's
      // top), each side meshed on its own crosses the other within its
      // chords. The old triangles (which crossed nothing) around each wrong
      // new one are held next round, the rest of the face meshed again
      // around them, and the junctions through them keep their nodes; in the
      // last rounds, or where nothing more is held, the face keeps all its
      // triangles.
      const bool hold = round + 2 < kRounds;
      for (size_t i = 0; i < wrong.size(); ++i) {
        const int t = wrong[i], f = m.tri_face[t];
        // The new triangle's box, grown by a quarter of its size: the old
        // ones are chords of the same surface, nearer to it or farther.
        Eigen::AlignedBox3d zone;
        for (int n : m.tris[t]) zone.extend(m.xyz[n]);
        const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.25 * zone.diagonal().norm());
        zone = Eigen::AlignedBox3d(zone.min() - margin, zone.max() + margin);
        auto& boxes = old_boxes[f];
        if (boxes.empty())
          for (int old : tris_of[f]) {
            boxes.emplace_back();
            for (int n : s.tris[old]) boxes.back().extend(s.xyz[n]);
          }
        std::vector<int> near;
        for (size_t j = 0; j < boxes.size(); ++j)
          if (zone.intersects(boxes[j])) near.push_back(tris_of[f][j]);
        // A new triangle turned over where the old ones are too (a
        // trailing edge thinner than the elements) is no worse than they.
        auto turned = [&](int old) { return inverted_triangle(s, g, static_cast<size_t>(old)); };
        if (i >= crossing_wrong && std::any_of(near.begin(), near.end(), turned)) continue;
        if (!hold || kept.count(f) || near.empty()) {
          blamed = kept.insert(f).second || blamed;
          continue;
        }
        for (int old : near) blamed = held.insert(old).second || blamed;
      }
      for (size_t k = 0; k < chains.size(); ++k)
        for (size_t j = 0; j + 1 < chains[k].nodes.size() && !frozen.count(k); ++j)
          for (int t : topo.edge_tris.at(edge_key(chains[k].nodes[j], chains[k].nodes[j + 1])))
            if (held.count(t)) frozen.insert(k);
    }
    // Nothing more to hold or keep: new triangles turned over alone are
    // taken as they are (the old ones were no better), crossings never.
    if (blamed) continue;
    if (more_crossings(hits.pairs)) return out;
    // The junction as it ends: each chain's new nodes or its old ones.
    std::vector<std::array<int, 2>> ends;
    for (size_t k = 0; k < chains.size(); ++k) {
      const Chain& c = chains[k];
      const bool substituted = c.usable && !frozen.count(k) && !kept.count(c.fa) && !kept.count(c.fb);
      std::vector<int> path = c.nodes;
      if (substituted) {
        path = {c.nodes.front()};
        path.insert(path.end(), c.id.begin(), c.id.end());
        path.push_back(c.nodes.back());
        out.junction_nodes += static_cast<int>(c.id.size());
      }
      for (size_t j = 0; j + 1 < path.size(); ++j)
        if (used[path[j]] >= 0 && used[path[j + 1]] >= 0) ends.push_back({used[path[j]], used[path[j + 1]]});
    }
    out.faces_remeshed = static_cast<int>(regions.size());
    out.faces_kept = static_cast<int>(kept.size());
    s = std::move(m);
    u.junction = std::move(ends);
    const JunctionSliverResult thin = remove_junction_slivers(s, g, h, u.junction, hits.pairs);
    out.thin_collapsed = thin.collapsed;
    out.thin_flipped = thin.flipped;
    out.thin_pinched = thin.pinched;
    measure_junction(s, g, u, 1e4 * tol);  // 1e-9 of the diagonal, as unite_meshes()
    return out;
  }
  return out;
}

}  // namespace sizemesh
