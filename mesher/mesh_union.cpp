// The mesh-level union of components: pieces taken one at a time into the base by CGAL corefinement.
//
// The steps: the tracked CGAL mesh and its checks (tracked_mesh.h), the
// corefinement's bookkeeping (corefine_tracking.h), slots closed before a
// union (close_gaps.h), the cut's bands remeshed (remesh_bands.h), and the
// result put back on the CAD faces as a SurfaceMesh (union_to_surface.h).
#include "mesher/mesh_union.h"

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <unordered_map>

#include "mesher/close_gaps.h"
#include "mesher/corefine_tracking.h"
#include "mesher/remesh_bands.h"
#include "mesher/target_sizes.h"
#include "mesher/tracked_mesh.h"
#include "mesher/union_to_surface.h"

namespace sizemesh {
using namespace mesh_union_detail;  // the union's steps
namespace {

// The triangles `ids` in pieces connected across edges: the closed ones
// (every edge used twice), largest first, and the triangles of open ones.
std::vector<std::vector<int>> closed_pieces(const SurfaceMesh& s, const std::vector<int>& ids, std::vector<int>& open) {
  std::vector<int> parent(ids.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (size_t i = 0; i < ids.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[ids[i]][k], b = s.tris[ids[i]][(k + 1) % 3];
      edges[std::minmax(a, b)].push_back(static_cast<int>(i));
    }
  std::vector<bool> open_root(ids.size(), false);
  for (const auto& [e, uses] : edges)
    for (size_t j = 1; j < uses.size(); ++j) parent[find(uses[j])] = find(uses[0]);
  for (const auto& [e, uses] : edges)
    if (uses.size() != 2) open_root[find(uses[0])] = true;
  std::map<int, std::vector<int>> by_root;
  for (size_t i = 0; i < ids.size(); ++i) {
    const int root = find(static_cast<int>(i));
    if (open_root[root]) open.push_back(ids[i]);
    else by_root[root].push_back(ids[i]);
  }
  std::vector<std::vector<int>> out;
  for (auto& [root, tris] : by_root) out.push_back(std::move(tris));
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.size() > y.size(); });
  return out;
}

}  // namespace

MeshUnionResult unite_meshes(SurfaceMesh& s, const Geometry& g, const SizeField& h,
                             const std::vector<std::vector<int>>& parts) {
  MeshUnionResult out;
  out.failures.assign(parts.size(), {});
  if (parts.empty()) return out;
  // Triangles per part; the rest is the base, its closed components united,
  // its open ones (sheets) kept as they are.
  std::unordered_map<int, int> part_of_face;
  for (size_t p = 0; p < parts.size(); ++p)
    for (int f : parts[p]) part_of_face[f] = static_cast<int>(p);
  std::vector<std::vector<int>> part_tris(parts.size());
  std::vector<int> rest;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const auto it = part_of_face.find(s.tri_face[t]);
    (it == part_of_face.end() ? rest : part_tris[it->second]).push_back(static_cast<int>(t));
  }
  // The pieces to unite: the rest's closed pieces (largest first), then each
  // part's: a part whose mesh is closed joins as its closed pieces, one at a
  // time (a component whose halves are closed shells that cross each other,
  // such as a T-tail's two halves through the fin, is united with itself
  // too); one whose mesh is open joins whole and fails, named. The rest's
  // open pieces (sheets) and the pieces that cannot take part (a mesh that
  // intersects itself) are kept as they are.
  std::vector<int> aside;
  std::vector<std::vector<int>> pieces = closed_pieces(s, rest, aside);
  const size_t rest_pieces = pieces.size();
  std::vector<int> part_of_piece(rest_pieces, -1);
  for (size_t p = 0; p < parts.size(); ++p) {
    std::vector<int> open;
    std::vector<std::vector<int>> closed = closed_pieces(s, part_tris[p], open);
    if (!open.empty() || closed.empty()) closed = {part_tris[p]};
    for (auto& tris : closed) pieces.push_back(std::move(tris)), part_of_piece.push_back(static_cast<int>(p));
  }

  // Target sizes at the nodes, for the band's edge length.
  const std::vector<double> node_h = target_sizes(s, h);

  std::unique_ptr<Tracked> base;
  std::set<int> base_nodes;
  // Per CAD face, the source triangles near a cut: uv hints for the projection.
  std::map<int, std::set<int>> near_cut;
  // A piece whose skin folds through itself waits until every other piece is
  // in the base: it joins only if its fold lies inside the base (the union
  // drops it there) and the union is then free of crossings.
  std::vector<size_t> waiting;
  // Source nodes moved to close a slot (close_gaps()): off their CAD faces.
  std::set<int> gap_moved;
  auto take = [&](size_t i, bool last_pass) {
    const bool is_part = i >= rest_pieces;
    auto fail = [&](const std::string& why) {
      if (is_part && out.failures[part_of_piece[i]].empty()) out.failures[part_of_piece[i]] = why;
      if (!is_part) ++out.rest_pieces_apart;
      aside.insert(aside.end(), pieces[i].begin(), pieces[i].end());
    };
    auto part = std::make_unique<Tracked>();
    std::string why;
    std::vector<FI> crossing;
    if (pieces[i].empty()) why = "it has no triangles";
    else if (!build(s, pieces[i], *part)) why = "its mesh is not manifold";
    for (VI v : part->m.vertices())
      if (why.empty() && base_nodes.count(part->node[v])) why = "its mesh shares nodes with the rest";
    if (why.empty()) why = unfit(*part, crossing);
    const bool folded = why == kCrossesItself;
    if (folded && !last_pass) return waiting.push_back(i);
    if (folded && base && inside_base(part->m, crossing, base->m)) why.clear();
    else if (folded) why = "its mesh intersects itself outside the other components";
    if (!why.empty()) return fail(why);
    for (VI v : part->m.vertices()) base_nodes.insert(part->node[v]);
    if (!base) {  // the start
      base = std::move(part);
      return;
    }
    auto before = std::make_unique<Tracked>(*base);
    std::set<int> moved_now;
    if (!folded) close_gaps(*part, *base, node_h, moved_now);
    // A union of volumes holds the larger of the two and no more than both:
    // a corefinement that went wrong (a folded skin) can give less, even
    // nothing, and still cross nowhere. A folded piece's own volume counts
    // its fold twice or not at all, so only the base's bounds it then.
    const double volume_base = PMP::volume(base->m), volume_part = PMP::volume(part->m);
    Follow follow;
    follow.s->a = base.get();
    follow.s->b = part.get();
    const CGAL::Bbox_3 part_box = PMP::bbox(part->m);
    auto cut_now = base->m.add_property_map<EI, bool>("e:cut_now", false).first;
    std::string wrong;
    try {
      if (!PMP::corefine_and_compute_union(base->m, part->m, base->m,
                                           PMP::parameters::visitor(follow).throw_on_self_intersection(!folded),
                                           PMP::parameters::default_values(),
                                           PMP::parameters::edge_is_constrained_map(cut_now)))
        wrong = "the corefinement of its mesh with the rest failed";
      else if (folded && crosses_within(base->m, part_box))
        wrong = "its mesh intersects itself, and its union with the rest does too";
      const double v = wrong.empty() ? PMP::volume(base->m) : 0.0;
      const double slack = 1e-6 * (volume_base + std::abs(volume_part));
      const double least = folded ? volume_base : std::max(volume_base, volume_part);
      const double most = volume_base + volume_part;
      if (wrong.empty() && v < least - slack)
        wrong = "its union with the rest would bound " + std::to_string(v) + ", less than " + std::to_string(least) +
                " (a corefinement gone wrong)";
      else if (wrong.empty() && !folded && v > most + slack)
        wrong = "its union with the rest would bound " + std::to_string(v) + ", more than both, " +
                std::to_string(most) + " (a corefinement gone wrong)";
    } catch (const std::exception&) {
      wrong = "the corefinement of its mesh with the rest failed";
    }
    if (!wrong.empty()) {
      for (VI v : part->m.vertices()) base_nodes.erase(part->node[v]);
      base = std::move(before);
      // A piece wholly inside the rest adds nothing to the union: its
      // triangles go, and it counts as united.
      Tracked whole;  // the piece as it was (the corefinement changed part)
      if (build(s, pieces[i], whole)) {
        const std::vector<FI> all(whole.m.faces().begin(), whole.m.faces().end());
        if (inside_base(whole.m, all, base->m)) return;
      }
      return fail(wrong);
    }
    gap_moved.insert(moved_now.begin(), moved_now.end());
    adopt_orphans(*base);
    for (EI e : base->m.edges())
      if (cut_now[e]) base->cut[e] = true;
    base->m.remove_property_map(cut_now);
    // The corefinement's output is the same from run to run but not in the
    // same order (its new vertices and faces come in an order of its own
    // bookkeeping): the next piece's gap closing and corefinement, and the
    // band re-mesh, follow the order they find. Renumbered by the geometry
    // alone, each step starts from the same mesh every run.
    renumber(*base);
  };
  for (size_t i = 0; i < pieces.size(); ++i) take(i, false);
  for (size_t i : waiting) take(i, true);
  for (size_t p = 0; p < parts.size(); ++p) out.united += out.failures[p].empty();
  out.gap_nodes_closed = static_cast<int>(gap_moved.size());
  if (!base) base = std::make_unique<Tracked>();
  renumber(*base);
  remesh_bands(*base, s, g, node_h, near_cut, out);
  base->m.collect_garbage();
  to_surface_mesh(s, g, *base, gap_moved, near_cut, aside, out);
  return out;
}

}  // namespace sizemesh
