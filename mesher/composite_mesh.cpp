#include "mesher/composite_mesh.h"

#include <algorithm>
#include <cmath>

#include "core/predicates.h"

namespace sizemesh::composite_detail {



CompositeMesh::CompositeMesh(SurfaceMesh& s, const Geometry& g, const SizeField& h, std::unordered_set<uint64_t> hard,
                             std::vector<char> corner)
    : s_(s), g_(g), h_(h), hard_(std::move(hard)), corner_(std::move(corner)), xyz_(s.xyz), tris_(s.tris),
      tri_face_(s.tri_face), dead_(s.tris.size(), 0), changed_(s.tris.size(), 0), node_tris_(s.xyz.size()),
      hard_degree_(s.xyz.size(), 0), size_(s.xyz.size(), 0.0), place_(s.xyz.size()), normal_(s.xyz.size()),
      has_normal_(s.xyz.size(), 0), ref_face_(s.tri_face),
      ref_uv_(s.tri_uv) {
  for (size_t t = 0; t < tris_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int n = tris_[t][k];
      node_tris_[n].push_back(static_cast<int>(t));
      if (!place_[n].face) place_[n] = {tri_face_[t], s.tri_uv[t][k]};
      input_uv_.emplace((static_cast<uint64_t>(n) << 32) | static_cast<uint32_t>(tri_face_[t]), s.tri_uv[t][k]);
    }
  for (uint64_t e : hard_) {
    ++hard_degree_[static_cast<int>(e >> 32)];
    ++hard_degree_[static_cast<int>(e & 0xffffffffu)];
  }
  size_.assign(xyz_.size(), -1.0);  // asked when first needed
  // Nodes ranked by position: the mesher numbers them in the order its
  // threads finish faces, and the operations must not depend on it.
  std::vector<int> order(xyz_.size());
  for (size_t n = 0; n < order.size(); ++n) order[n] = static_cast<int>(n);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::lexicographical_compare(xyz_[a].data(), xyz_[a].data() + 3, xyz_[b].data(), xyz_[b].data() + 3);
  });
  rank_.assign(xyz_.size(), 0);
  for (size_t i = 0; i < order.size(); ++i) rank_[order[i]] = static_cast<int>(i);
  curve_.assign(xyz_.size(), 0);
  slid_.assign(xyz_.size(), 0);
  for (size_t n = 0; n < xyz_.size(); ++n)
    if (s.node_dim[n] == 1) curve_[n] = s.node_entity[n];
  reference_ = std::make_unique<TriangleBVH>(s.xyz, s.tris);
}

std::vector<int> CompositeMesh::neighbours(int n) const {
  std::vector<int> out;
  for (int t : node_tris_[n])
    for (int m : tris_[t])
      if (m != n) out.push_back(m);
  std::sort(out.begin(), out.end(), before_);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::array<int, 2> CompositeMesh::edge_tris(int a, int b) const {
  std::array<int, 2> out{-1, -1};
  int found = 0;
  for (int t : node_tris_[a])
    if (std::find(tris_[t].begin(), tris_[t].end(), b) != tris_[t].end()) {
      if (found == 2) return {-1, -1};  // more than two: never touched
      out[found++] = t;
    }
  return out;
}

Vec3 CompositeMesh::normal(const std::array<int, 3>& t) const {
  return (xyz_[t[1]] - xyz_[t[0]]).cross(xyz_[t[2]] - xyz_[t[0]]);
}

Vec3 CompositeMesh::surface_normal(const Place& at) const {
  const SurfaceD1 d = g_.eval_face(at.face, at.uv);
  Vec3 n = d.du.cross(d.dv);
  if (!(n.norm() > 0) || !n.allFinite()) return Vec3::Zero();
  n.normalize();
  return g_.face_reversed(at.face) ? Vec3(-n) : n;
}

bool CompositeMesh::facing(const std::vector<std::array<Vec3, 3>>& tris, const Place& at) const {
  const Vec3 ns = surface_normal(at);
  if (ns.isZero()) return true;
  for (const auto& p : tris) {
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (n.dot(ns) < 0.3 * n.norm()) return false;
  }
  return true;
}

Vec3 CompositeMesh::node_normal(int n) {
  if (!free(n)) return Vec3::Zero();
  if (!has_normal_[n]) normal_[n] = surface_normal(place_[n]), has_normal_[n] = 1;
  return normal_[n];
}

double CompositeMesh::sag(const Vec3& xa, const Vec3& na, const Vec3& xb, const Vec3& nb) {
  if (na.isZero() || nb.isZero()) return 0;
  const double theta = std::acos(std::clamp(na.dot(nb), -1.0, 1.0));
  return (xb - xa).norm() * theta / 8;
}

bool CompositeMesh::accurate(const Vec3& xa, const Vec3& na, const Vec3& xb, const Vec3& nb, int face,
                             double old) const {
  const double s = sag(xa, na, xb, nb);
  if (s <= old * (1 + 1e-9)) return true;
  const double turn = h_.accuracy().turn(face), deviation = h_.accuracy().deviation;
  if (turn > 0 && std::acos(std::clamp(na.dot(nb), -1.0, 1.0)) > turn) return false;
  // A triangle's centroid lies 4/3 as far off as its edges' middles.
  return !(deviation > 0 && s > 0.75 * deviation);
}

double CompositeMesh::star_min_angle(const std::vector<int>& tris) const {
  double m = 180;
  for (int t : tris) m = std::min(m, min_angle_deg(xyz_[tris_[t][0]], xyz_[tris_[t][1]], xyz_[tris_[t][2]]));
  return m;
}

bool CompositeMesh::project(const Vec3& p, double reach, Vec3& x, Place& at) const {
  const TriangleBVH::Closest c = reference_->closest(p);
  if (c.tri < 0) return false;
  const int f = ref_face_[c.tri];
  const auto& uv = ref_uv_[c.tri];
  Vec2 guess = c.weights[0] * uv[0] + c.weights[1] * unwrap_uv(g_, f, uv[1], uv[0]) +
               c.weights[2] * unwrap_uv(g_, f, uv[2], uv[0]);
  if (!g_.project_to_face(f, p, guess)) return false;
  x = g_.eval_face(f, guess).p;
  if (!x.allFinite() || (x - p).norm() > reach) return false;
  at = {f, guess};
  return true;
}

int CompositeMesh::add_node(const Vec3& x, const Place& at) {
  xyz_.push_back(x);
  place_.push_back(at);
  rank_.push_back(static_cast<int>(rank_.size()));
  curve_.push_back(0);
  slid_.push_back(0);
  normal_.push_back(surface_normal(at));
  has_normal_.push_back(1);
  node_tris_.emplace_back();
  hard_degree_.push_back(0);
  corner_.push_back(0);
  int hint = -1;
  size_.push_back(h_.at(at.face, at.uv, hint));
  return num_nodes() - 1;
}

int CompositeMesh::add_tri(const std::array<int, 3>& t, int face) {
  const int id = static_cast<int>(tris_.size());
  tris_.push_back(t);
  tri_face_.push_back(face);
  dead_.push_back(0);
  changed_.push_back(1);
  for (int n : t) node_tris_[n].push_back(id);
  return id;
}

void CompositeMesh::kill(int t) {
  dead_[t] = 1;
  for (int n : tris_[t]) {
    auto& v = node_tris_[n];
    v.erase(std::remove(v.begin(), v.end(), t), v.end());
  }
}





std::vector<int> CompositeMesh::write_back(std::vector<char>* fresh_out) {
  const int n_in = static_cast<int>(s_.xyz.size());
  std::vector<char> moved(xyz_.size(), 0);
  for (int n = 0; n < num_nodes(); ++n) moved[n] = n >= n_in || xyz_[n] != s_.xyz[n];
  std::vector<int> id(xyz_.size(), -1);
  SurfaceMesh out;
  out.failures = s_.failures;
  out.stats = s_.stats;
  for (size_t t = 0; t < tris_.size(); ++t) {
    if (dead_[t]) continue;
    std::array<int, 3> tr = tris_[t];
    int f = tri_face_[t];
    std::array<Vec2, 3> uv{};
    bool fresh = changed_[t] || t >= s_.tris.size();
    for (int n : tr) fresh = fresh || moved[n];
    if (!fresh) {
      uv = s_.tri_uv[t];
    } else {
      // The face under the centroid, and each corner's uv on it: projected
      // from the uv there, so all three lie on one branch of a periodic
      // surface.
      const Vec3 centre = (xyz_[tr[0]] + xyz_[tr[1]] + xyz_[tr[2]]) / 3.0;
      const TriangleBVH::Closest c = reference_->closest(centre);
      Vec2 guess = place_[tr[0]].uv;
      if (c.tri >= 0) {
        f = ref_face_[c.tri];
        const auto& r = ref_uv_[c.tri];
        guess = c.weights[0] * r[0] + c.weights[1] * unwrap_uv(g_, f, r[1], r[0]) +
                c.weights[2] * unwrap_uv(g_, f, r[2], r[0]);
      }
      // A corner on another face (across a virtual curve) keeps the uv
      // there: f's surface extended past its trim may fold anywhere.
      double longest = 0;
      for (int k = 0; k < 3; ++k) longest = std::max(longest, (xyz_[tr[k]] - xyz_[tr[(k + 1) % 3]]).norm());
      // Newton from the uv under the centroid keeps the three on one branch
      // of a periodic surface; where it does not reach a node of f, the
      // node's own uv does.
      for (int k = 0; k < 3; ++k) {
        const int n = tr[k];
        Vec2 q = guess;
        const bool found = g_.project_to_face(f, xyz_[n], q);
        const double off = found ? (g_.eval_face(f, q).p - xyz_[n]).norm() : HUGE_VAL;
        uv[k] = q;
        if (off <= 1e-12 * longest) continue;
        // A node the input held on f off its surface (a junction node the
        // union left between two surfaces) keeps the input's uv there.
        const auto in = n < n_in && !moved[n] ? input_uv_.find((static_cast<uint64_t>(n) << 32) | static_cast<uint32_t>(f))
                                                : input_uv_.end();
        if (in != input_uv_.end() && (in->second - guess).norm() <= 2 * (q - guess).norm() + 1e-9 * longest)
          uv[k] = in->second;
        else if (place_[n].face == f) uv[k] = unwrap_uv(g_, f, place_[n].uv, guess);
        else if (!(off <= 1e-3 * longest)) uv[k] = guess;
      }
    }
    for (int n : tr) id[n] = 0;
    if (fresh_out) fresh_out->push_back(fresh);
    out.tris.push_back(tr);
    out.tri_face.push_back(f);
    out.tri_uv.push_back(uv);
  }
  // Nodes in their order, those no triangle uses gone.
  for (int n = 0; n < num_nodes(); ++n) {
    if (id[n] < 0) continue;
    id[n] = static_cast<int>(out.xyz.size());
    out.xyz.push_back(xyz_[n]);
    const bool kept = n < n_in && (!moved[n] || slid_[n]);  // a node slid along its curve stays on it
    out.node_dim.push_back(kept ? s_.node_dim[n] : 2);
    out.node_entity.push_back(kept ? s_.node_entity[n] : place_[n].face);
  }
  for (auto& tr : out.tris)
    for (int& n : tr) n = id[n];
  s_ = std::move(out);
  id.resize(n_in);
  return id;
}



}  // namespace sizemesh::composite_detail
