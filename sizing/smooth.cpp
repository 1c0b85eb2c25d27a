#include "sizing/smooth.h"

#include "core/stopwatch.h"
#include "core/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "sizing/lp_smooth.h"

namespace sizemesh {

namespace {


// Relative slack kept below a bound so that round-off never leaves a size above it.
constexpr double kSlack = 1e-12;
// A corrected triangle is left this far (relative) below its gradient bound.
// Corrected exactly to the bound, a triangle is pushed over it again by every
// later lowering of its smallest corner, however tiny, and the rounds creep
// on without end; with this margin each new correction lowers a size by a
// finite step, so the rounds end.
constexpr double kTriangleMargin = 1e-3;
// Rounds in which a triangle may be corrected by the least change (which
// lowers its middle corner too, the smallest corner of other triangles, so
// that rounds could creep on); after them, by the paper's rules, which end.
constexpr int kLeastChangeRounds = 20;
// Least share of its middle size the least change may keep (below it, the
// paper's rules): a larger cut spreads to the triangles around that corner.
constexpr double kLeastChangeKeep = 0.9;
// Rounds after which the triangles still over their bound are left as they
// are. Corrections on slivers of the background (near-collinear triangles
// along a blunt trailing edge) can creep on, each lowering a size by a
// fraction of a percent; setting such a triangle's sizes equal instead would
// push its neighbours over their bounds in turn and flood the whole mesh
// with its smallest size.
constexpr int kMaxRounds = 1000;

// Gradient of the linear interpolant on a triangle in its own plane (Eq. 11),
// written with size differences from the corner `o0` so that equal sizes give
// exactly zero and thin triangles lose no digits:
//   |grad h|^2 = (a^2 G22 - 2 a b G12 + b^2 G11) / det G,
// a = h_o1 - h_o0, b = h_o2 - h_o0, G the Gram matrix of e1 = p_o1 - p_o0,
// e2 = p_o2 - p_o0 (this equals the paper's H^T K H).
struct TriangleFrame {
  double g11, g12, g22, det;
  bool degenerate;
};

TriangleFrame frame(const BackgroundMesh& bg, int t, const int o[3]) {
  const auto& tr = bg.tris[t];
  const Vec3 e1 = bg.xyz[tr[o[1]]] - bg.xyz[tr[o[0]]], e2 = bg.xyz[tr[o[2]]] - bg.xyz[tr[o[0]]];
  TriangleFrame f{e1.dot(e1), e1.dot(e2), e2.dot(e2), e1.cross(e2).squaredNorm(), false};
  const double l2 = std::max({f.g11, f.g22, (e2 - e1).squaredNorm()});
  f.degenerate = !(f.det > 1e-24 * l2 * l2);
  return f;
}

double gradient2(const TriangleFrame& f, double a, double b) {
  return std::max(0.0, (a * a * f.g22 - 2 * a * b * f.g12 + b * b * f.g11) / f.det);
}

// The least change that meets Eq. 11 with h0 kept: among the (a, b) =
// (h1' - h0, h2' - h0) in the ellipse |grad h|^2 det = x^T M x <= L^2 det,
// M = [[G22, -G12], [-G12, G11]], and in the box 0 <= a <= h1 - h0,
// 0 <= b <= h2 - h0, the one that keeps the most of both sizes,
// max a / h1 + b / h2: x = L u / sqrt(c . u) with c = (1 / h1, 1 / h2) and
// u = det M^-1 c = (G11 c1 + G12 c2, G12 c1 + G22 c2); where that leaves the
// box, the bound side's size is kept (or zero) and the other is the
// ellipse's root there. Beyond the paper, whose rules lower the largest
// size first: on a needle whose short side is at its bound, that pulls the
// far corner down to the near side's size, where lowering the near side by
// a few percent lets the far corner keep its own. False (nothing changed)
// where the ellipse has no such point or h1 would lose more than
// 1 - kLeastChangeKeep of itself.
bool least_change(const TriangleFrame& f, double L, double h0, double& h1, double& h2) {
  const double A = h1 - h0, B = h2 - h0;
  if (!(h1 > 0) || !(h2 > 0)) return false;
  const double c1 = 1 / h1, c2 = 1 / h2;
  const double u1 = f.g11 * c1 + f.g12 * c2, u2 = f.g12 * c1 + f.g22 * c2;
  const double cu = c1 * u1 + c2 * u2;
  if (!(cu > 0)) return false;
  double x1 = L * u1 / std::sqrt(cu), x2 = L * u2 / std::sqrt(cu);
  // Largest b on the ellipse for a given a, and the other way round (NaN where none).
  auto b_at = [&](double a) { return (a * f.g12 + std::sqrt(f.det * (f.g11 * L * L - a * a))) / f.g11; };
  auto a_at = [&](double b) { return (b * f.g12 + std::sqrt(f.det * (f.g22 * L * L - b * b))) / f.g22; };
  if (x1 > A) x1 = A, x2 = std::min(B, b_at(A));
  else if (x2 > B) x2 = B, x1 = std::min(A, a_at(B));
  else if (x1 < 0) x1 = 0, x2 = std::min(B, L * std::sqrt(f.det / f.g11));
  else if (x2 < 0) x2 = 0, x1 = std::min(A, L * std::sqrt(f.det / f.g22));
  if (!(x1 >= 0) || !(x2 >= 0) || !(x1 <= A) || !(x2 <= B)) return false;
  if (gradient2(f, x1, x2) > L * L * (1 + 1e-9)) return false;
  if (h0 + x1 < kLeastChangeKeep * h1) return false;
  // Only lowered (h0 + (h1 - h0) need not give h1 back to the last bit).
  const double n1 = std::min(h1, h0 + x1), n2 = std::min(h2, h0 + x2);
  if (!(n1 < h1) && !(n2 < h2)) return false;
  h1 = n1;
  h2 = n2;
  return true;
}

// Paper 3.3 correction of one violating triangle, corners sorted h0 <= h1 <= h2,
// L = ln(beta), a = h1 - h0, b = h2 - h0:
// (1) lower h2 so that |grad h| = L: the quadratic in b has the root
//     b = (a G12 + sqrt(det (G11 L^2 - a^2))) / G11, real whenever edge 0-1
//     meets its bound (the edge stage guarantees it); in the first
//     kLeastChangeRounds rounds the least change above comes first;
// (2) beyond the paper: in an obtuse triangle the middle size can be the
//     culprit (h2 is already below that root); then lower h1 the same way;
// (3) the paper's second rule: lower h1 and h2 together to h0 + L * height_0;
// (4) last resort: h1 = h2 = h0 (gradient zero).
// Sizes are only lowered; returns true when one changed.
bool correct_triangle(const BackgroundMesh& bg, int t, double log_beta, std::vector<double>& h, bool least) {
  const auto& tr = bg.tris[t];
  // (0) A corner lowered earlier in this round (by a neighbouring triangle)
  // leaves this triangle's sides over their Eq. 12 bound until the edge
  // stage runs again, and rules (1)-(3) assume they meet it: on a needle,
  // rule (3) would then pull the far corner down to the near side's size.
  // The sides are graded first, along themselves, as the edge stage would.
  bool graded = false;
  for (int pass = 0; pass < 2; ++pass)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) {
        if (j == k) continue;
        const double bound = h[tr[k]] + log_beta * (bg.xyz[tr[k]] - bg.xyz[tr[j]]).norm();
        if (bound < h[tr[j]]) h[tr[j]] = bound, graded = true;
      }
  int o[3] = {0, 1, 2};
  std::sort(o, o + 3, [&](int a, int b) { return h[tr[a]] < h[tr[b]]; });
  const TriangleFrame f = frame(bg, t, o);
  if (f.degenerate) return false;
  double& h0 = h[tr[o[0]]];
  double& h1 = h[tr[o[1]]];
  double& h2 = h[tr[o[2]]];
  const double L = log_beta * (1 - kTriangleMargin);
  auto lowered = [&](double& hv, double value) {
    if (!(value >= h0) || !(value < hv)) return false;
    hv = value;
    return true;
  };
  if (graded && gradient2(f, h1 - h0, h2 - h0) <= log_beta * log_beta) return true;
  const double a = h1 - h0, b = h2 - h0;
  // An edge at its own bound (between L and ln(beta)) gives the root of zero
  // discriminant: the gradient is then that edge's slope, within the bound.
  auto disc = [&](double g, double d) {
    const double q = f.det * (g * L * L - d * d);
    return q < 0 && d * d <= g * log_beta * log_beta * (1 + 1e-9) ? 0.0 : q;
  };
  const double disc_a = disc(f.g11, a);
  if (least && least_change(f, L, h0, h1, h2)) return true;
  if (disc_a >= 0 && lowered(h2, h0 + (a * f.g12 + std::sqrt(disc_a)) / f.g11)) return true;
  const double disc_b = disc(f.g22, b);
  if (disc_b >= 0 && lowered(h1, h0 + (b * f.g12 + std::sqrt(disc_b)) / f.g22)) return true;
  const double opposite2 = f.g11 + f.g22 - 2 * f.g12;  // |p2 - p1|^2; height_0 = 2A / |p2 - p1|
  const double both = h0 + L * std::sqrt(f.det / opposite2);
  const bool c1 = lowered(h1, std::min(h1, both)), c2 = lowered(h2, std::min(h2, both));
  if (c1 || c2) {
    if (gradient2(f, h1 - h0, h2 - h0) <= log_beta * log_beta) return true;
  }
  const bool d1 = lowered(h1, h0), d2 = lowered(h2, h0);
  return graded || c1 || c2 || d1 || d2;
}

}  // namespace

namespace {

// Vertex -> incident edges and triangles, and per-edge weights ln(beta_e) l_e.
struct Adjacency {
  std::vector<int> edge_start, edge_ids, tri_start, tri_ids;
  std::vector<double> w;
  Adjacency(const BackgroundMesh& bg, const std::vector<double>& edge_log_beta) {
    bg.vertex_edges(edge_start, edge_ids);
    w.resize(bg.edges.size());
    for (size_t e = 0; e < bg.edges.size(); ++e)
      w[e] = edge_log_beta[e] * (bg.xyz[bg.edges[e][0]] - bg.xyz[bg.edges[e][1]]).norm() * (1 - kSlack);
    vertex_triangles(bg.num_vertices(), bg.tris, tri_start, tri_ids);
  }
};

// Dijkstra from the seed vertices (their current sizes as distances): lowers
// every h_u above min over seeds (h_s + d(u, s)). With all vertices as seeds
// this is the exact edge stage; after a triangle correction only the lowered
// vertices need to be seeds. Appends every vertex it lowers to `lowered`.
void propagate(const BackgroundMesh& bg, const Adjacency& a, const std::vector<int>& seeds, std::vector<double>& h,
               std::vector<int>* lowered) {
  using Item = std::pair<double, int>;
  std::vector<Item> init;
  init.reserve(seeds.size());
  for (int v : seeds) init.emplace_back(h[v], v);
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap(std::greater<Item>(), std::move(init));
  while (!heap.empty()) {
    auto [d, v] = heap.top();
    heap.pop();
    if (d > h[v]) continue;
    for (int i = a.edge_start[v]; i < a.edge_start[v + 1]; ++i) {
      const int e = a.edge_ids[i];
      const int u = bg.edges[e][0] == v ? bg.edges[e][1] : bg.edges[e][0];
      const double cand = d + a.w[e];
      if (cand < h[u]) {
        h[u] = cand;
        heap.emplace(cand, u);
        if (lowered) lowered->push_back(u);
      }
    }
  }
}

std::vector<int> all_vertices(const BackgroundMesh& bg) {
  std::vector<int> v(bg.num_vertices());
  for (int i = 0; i < bg.num_vertices(); ++i) v[i] = i;
  return v;
}

}  // namespace

void smooth_edges(const BackgroundMesh& bg, const std::vector<double>& edge_log_beta, std::vector<double>& h) {
  const Adjacency a(bg, edge_log_beta);
  propagate(bg, a, all_vertices(bg), h, nullptr);
}

double triangle_gradient(const BackgroundMesh& bg, const std::vector<double>& h, int t) {
  static const int o[3] = {0, 1, 2};
  const TriangleFrame f = frame(bg, t, o);
  if (f.degenerate) return -1;
  const auto& tr = bg.tris[t];
  return std::sqrt(gradient2(f, h[tr[1]] - h[tr[0]], h[tr[2]] - h[tr[0]]));
}

SmoothStats smooth(const BackgroundMesh& bg, SizeMap& m, EdgeSolver solver) {
  SmoothStats s;
  m.h = m.h_initial;
  const int nt = bg.num_triangles();
  for (int t = 0; t < nt; ++t) s.degenerate_triangles += triangle_gradient(bg, m.h, t) < 0;
  Stopwatch clock;
  const Adjacency adj(bg, m.edge_log_beta);
  if (solver == EdgeSolver::LpSolve) smooth_edges_lp(bg, m.edge_log_beta, m.h);
  else propagate(bg, adj, all_vertices(bg), m.h, nullptr);
  s.t_edge += clock.lap();
  // Alternate triangle corrections (Eq. 11) and edge propagation (Eq. 12),
  // each round looking only at triangles around the vertices that changed.
  std::vector<int> work(nt);
  for (int t = 0; t < nt; ++t) work[t] = t;
  std::vector<int> stamp(nt, -1);
  for (int round = 0; !work.empty(); ++round) {
    clock.lap();
    if (round == kMaxRounds) {
      for (int t : work) s.steep_triangles += triangle_gradient(bg, m.h, t) > m.tri_log_beta[t];
      break;
    }
    std::vector<int> changed;
    for (int t : work) {
      const double lb = m.tri_log_beta[t];
      if (!(triangle_gradient(bg, m.h, t) > lb)) continue;
      const auto& tr = bg.tris[t];
      const double before[3] = {m.h[tr[0]], m.h[tr[1]], m.h[tr[2]]};
      correct_triangle(bg, t, lb, m.h, round < kLeastChangeRounds);
      for (int k = 0; k < 3; ++k)
        if (m.h[tr[k]] < before[k]) changed.push_back(tr[k]);
      ++s.triangle_corrections;
    }
    s.t_triangle += clock.lap();
    s.rounds = round + 1;
    if (changed.empty()) break;
    clock.lap();
    std::vector<int> touched = changed;
    propagate(bg, adj, changed, m.h, &touched);
    s.t_edge += clock.lap();
    work.clear();
    for (int v : touched)
      for (int i = adj.tri_start[v]; i < adj.tri_start[v + 1]; ++i)
        if (stamp[adj.tri_ids[i]] != round) {
          stamp[adj.tri_ids[i]] = round;
          work.push_back(adj.tri_ids[i]);
        }
    std::sort(work.begin(), work.end());  // the same order whatever the history
  }
  for (int v = 0; v < bg.num_vertices(); ++v)
    if (m.h[v] < m.h_initial[v]) {
      ++s.lowered;
      s.max_reduction = std::max(s.max_reduction, m.h_initial[v] / m.h[v]);
    }
  return s;
}

GradationCheck check_gradation(const BackgroundMesh& bg, const SizeMap& m) {
  GradationCheck c;
  for (size_t e = 0; e < bg.edges.size(); ++e) {
    const int a = bg.edges[e][0], b = bg.edges[e][1];
    const double l = (bg.xyz[a] - bg.xyz[b]).norm();
    const double dh = std::abs(m.h[a] - m.h[b]);
    if (dh == 0) continue;
    c.max_edge_ratio = std::max(c.max_edge_ratio, l > 0 ? dh / (m.edge_log_beta[e] * l) : INFINITY);
  }
  c.triangle_ratio.assign(bg.num_triangles(), 0.0);
  for (int t = 0; t < bg.num_triangles(); ++t) {
    const double g = triangle_gradient(bg, m.h, t);
    if (g < 0) continue;
    c.triangle_ratio[t] = m.tri_log_beta[t] > 0 ? g / m.tri_log_beta[t] : (g > 0 ? INFINITY : 0);
    c.max_triangle_ratio = std::max(c.max_triangle_ratio, c.triangle_ratio[t]);
  }
  return c;
}

}  // namespace sizemesh
