// Classified background mesh from the B-rep tessellation (paper 3.1).
//
// Vertices are merged through topology, not coordinates: B-rep points give the
// dimension-0 vertices, each curve's polygon (shared by every face it bounds,
// BRepMesh discretises an edge once) gives its dimension-1 vertices, and the
// remaining triangulation nodes of a face are its own dimension-2 vertices.
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "cad/tessellate.h"

namespace sizemesh {
namespace {

// A curve's chain of global vertices with the curve parameter of each.
struct Chain {
  std::vector<int> vertex;
  std::vector<double> t;
};

}  // namespace

void build_adjacency(FacePatch& patch) {
  // Across the side opposite corner k: the side (k+1, k+2).
  const std::vector<std::array<int, 3>> nbr = triangle_neighbours(patch.tris);
  patch.adj.resize(nbr.size());
  for (size_t t = 0; t < nbr.size(); ++t) patch.adj[t] = {nbr[t][1], nbr[t][2], nbr[t][0]};
}

namespace {

class Builder {
 public:
  Builder(const Tessellation& tess, const Geometry& g, BackgroundMesh& bg) : tess_(tess), g_(g), bg_(bg) {}

  void run() {
    const int np = g_.num_points();
    for (int p = 1; p <= np; ++p) add_vertex(g_.point_xyz(p), 0, p);
    chains_.resize(g_.num_curves());
    bg_.patches.resize(tess_.faces.size());
    for (int f = 1; f <= static_cast<int>(tess_.faces.size()); ++f) build_patch(f);
    std::vector<CurveEdge> curve_edges;
    for (int c = 0; c < static_cast<int>(chains_.size()); ++c)
      for (size_t i = 1; i < chains_[c].vertex.size(); ++i)
        if (chains_[c].vertex[i - 1] != chains_[c].vertex[i])
          curve_edges.push_back({{chains_[c].vertex[i - 1], chains_[c].vertex[i]}, c + 1});
    assemble_background(bg_, g_, curve_edges);
  }

 private:
  int add_vertex(const Vec3& p, int dim, int entity) {
    bg_.xyz.push_back(p);
    bg_.dim.push_back(static_cast<int8_t>(dim));
    bg_.entity.push_back(entity);
    bg_.curve_t.push_back(std::numeric_limits<double>::quiet_NaN());
    return bg_.num_vertices() - 1;
  }

  // Global vertex of a curve's end (point id) or -1 if the curve has no vertex there.
  int point_vertex(int point) const { return point > 0 ? point - 1 : -1; }

  // Maps the nodes of a curve's polygon on one face triangulation to global vertices.
  void map_curve_nodes(const FaceTessellation& ft, const FaceTessellation::CurveUse& use,
                       std::vector<int>& local_to_global) {
    const int curve = use.curve;
    const int n = static_cast<int>(use.nodes.size());
    const std::vector<double>& params = use.t;
    if (g_.curve_degenerated(curve)) {
      const int v = point_vertex(g_.curve_start_point(curve));
      for (int i = 0; i < n; ++i) local_to_global[use.nodes[i]] = v;
      return;
    }
    Chain& chain = chains_[curve - 1];
    if (chain.vertex.empty()) {
      // First face to use this curve: create its vertices in parameter order.
      std::vector<int> order(n);
      for (int i = 0; i < n; ++i) order[i] = i;
      if (n > 1 && params[0] > params[n - 1]) std::reverse(order.begin(), order.end());
      const int start = point_vertex(g_.curve_start_point(curve)), end = point_vertex(g_.curve_end_point(curve));
      for (int j = 0; j < n; ++j) {
        const int i = order[j];
        int v;
        if (j == 0 && start >= 0) v = start;
        else if (j == n - 1 && end >= 0) v = end;
        else {
          v = add_vertex(ft.xyz[use.nodes[i]], 1, curve);
          bg_.curve_t[v] = params[i];
        }
        chain.vertex.push_back(v);
        chain.t.push_back(params[i]);
      }
    }
    // Every use (this face, other faces, a seam's second side) maps by parameter.
    for (int i = 0; i < n; ++i) {
      auto it = std::lower_bound(chain.t.begin(), chain.t.end(), params[i]);
      size_t j = static_cast<size_t>(it - chain.t.begin());
      if (j == chain.t.size() || (j > 0 && std::abs(chain.t[j - 1] - params[i]) < std::abs(chain.t[j] - params[i])))
        j = j == 0 ? 0 : j - 1;
      local_to_global[use.nodes[i]] = chain.vertex[j];
    }
  }

  void build_patch(int f) {
    FacePatch& patch = bg_.patches[f - 1];
    patch.face = f;
    const FaceTessellation& ft = tess_.faces[f - 1];
    if (ft.tris.empty()) {
      if (g_.face_area(f) > 0) bg_.faces_without_patch.push_back(f);
      return;
    }
    const int n = static_cast<int>(ft.xyz.size());
    std::vector<int> local_to_global(n, -1);
    for (const auto& use : ft.curves) map_curve_nodes(ft, use, local_to_global);
    for (int i = 0; i < n; ++i)
      if (local_to_global[i] < 0) local_to_global[i] = add_vertex(ft.xyz[i], 2, f);
    patch.vertex = local_to_global;
    patch.uv = ft.uv;
    for (std::array<int, 3> lt : ft.tris) {
      const Vec2 e1 = patch.uv[lt[1]] - patch.uv[lt[0]], e2 = patch.uv[lt[2]] - patch.uv[lt[0]];
      if (e1.x() * e2.y() - e1.y() * e2.x() < 0) std::swap(lt[1], lt[2]);  // counter-clockwise in uv
      patch.tris.push_back(lt);
    }
    build_adjacency(patch);
  }

  const Tessellation& tess_;
  const Geometry& g_;
  BackgroundMesh& bg_;
  std::vector<Chain> chains_;
};

}  // namespace

void assemble_background(BackgroundMesh& bg, const Geometry& g, const std::vector<CurveEdge>& curve_edges) {
  // Global triangles, patch by patch, oriented as each face lies in its shell.
  bg.tris.clear();
  bg.tri_face.clear();
  for (FacePatch& patch : bg.patches) {
    if (patch.face == 0) continue;
    const bool reversed = g.face_reversed(patch.face);
    patch.global_tri.assign(patch.tris.size(), -1);
    for (size_t t = 0; t < patch.tris.size(); ++t) {
      std::array<int, 3> v;
      for (int k = 0; k < 3; ++k) v[k] = patch.vertex[patch.tris[t][k]];
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;  // collapsed onto a pole
      if (reversed) std::swap(v[1], v[2]);
      patch.global_tri[t] = bg.num_triangles();
      bg.tris.push_back(v);
      bg.tri_face.push_back(patch.face);
    }
  }
  // Edges: the curves' first, then every triangle side.
  bg.edges.clear();
  bg.edge_curve.clear();
  std::unordered_map<uint64_t, int> index;
  index.reserve(bg.tris.size() * 2);
  auto add = [&](int a, int b, int curve) {
    auto [it, fresh] = index.emplace(edge_key(a, b), static_cast<int>(bg.edges.size()));
    if (fresh) {
      bg.edges.push_back({std::min(a, b), std::max(a, b)});
      bg.edge_curve.push_back(curve);
    } else if (curve) {
      bg.edge_curve[it->second] = curve;
    }
    return it->second;
  };
  for (const CurveEdge& e : curve_edges) add(e.v[0], e.v[1], e.curve);
  bg.tri_edges.resize(bg.tris.size());
  for (size_t t = 0; t < bg.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) bg.tri_edges[t][k] = add(bg.tris[t][k], bg.tris[t][(k + 1) % 3], 0);
  // Vertex uses (CSR).
  const int nv = bg.num_vertices();
  bg.use_start.assign(nv + 1, 0);
  for (const auto& p : bg.patches)
    for (int v : p.vertex) ++bg.use_start[v + 1];
  for (int v = 0; v < nv; ++v) bg.use_start[v + 1] += bg.use_start[v];
  bg.use_face.resize(bg.use_start[nv]);
  bg.use_local.resize(bg.use_start[nv]);
  std::vector<int> fill(bg.use_start.begin(), bg.use_start.end() - 1);
  for (const auto& p : bg.patches)
    for (int l = 0; l < static_cast<int>(p.vertex.size()); ++l) {
      const int slot = fill[p.vertex[l]]++;
      bg.use_face[slot] = p.face;
      bg.use_local[slot] = l;
    }
}

BackgroundMesh build_background_mesh(const Tessellation& tess, const Geometry& g) {
  BackgroundMesh bg;
  Builder(tess, g, bg).run();
  return bg;
}

BackgroundMesh build_background_mesh(const Model& model, const BackgroundOptions& options) {
  return build_background_mesh(tessellate(model, options), model);
}

double BackgroundMesh::area() const {
  double a = 0;
  for (const auto& t : tris) a += 0.5 * (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm();
  return a;
}

std::vector<int> BackgroundMesh::edge_valence() const {
  std::vector<int> val(edges.size(), 0);
  for (const auto& te : tri_edges)
    for (int e : te) ++val[e];
  return val;
}

std::unordered_map<uint64_t, int> BackgroundMesh::edge_index() const {
  std::unordered_map<uint64_t, int> index;
  index.reserve(edges.size() * 2);
  for (size_t e = 0; e < edges.size(); ++e) index.emplace(edge_key(edges[e][0], edges[e][1]), static_cast<int>(e));
  return index;
}

void BackgroundMesh::vertex_edges(std::vector<int>& start, std::vector<int>& ids) const {
  const int nv = num_vertices();
  start.assign(nv + 1, 0);
  for (const auto& e : edges) {
    ++start[e[0] + 1];
    ++start[e[1] + 1];
  }
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  ids.resize(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    ids[fill[edges[e][0]]++] = e;
    ids[fill[edges[e][1]]++] = e;
  }
}

}  // namespace sizemesh
