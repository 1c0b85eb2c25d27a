// The advancing front itself (front.h): its edges, each by node pair in a
// map, by metric length in a heap and by uv box in a grid, and the alive
// edges and nodes near a box (gather()), which the checks and steps look at.
#include "mesher/front.h"

#include <algorithm>

namespace sizemesh::detail {

void Front::add_edge(int a, int b) {
  FrontEdge e;
  e.a = a;
  e.b = b;
  const double ha = fm_.s[a].h, hb = fm_.s[b].h;
  e.key = pole_pair(a, b) ? 0.0 : (fm_.s[b].p - fm_.s[a].p).norm() / (0.5 * (ha + hb));
  const int id = static_cast<int>(edges_.size());
  edges_.push_back(e);
  stamp_.push_back(0);
  map_[code(a, b)] = id;
  grid_.insert(id, fm_.uv[a], fm_.uv[b]);
  heap_.push({e.key, id});
  ++alive_;
  if (edges_.size() >= 4 * grid_edges_) rebuild_grid();
}

void Front::rebuild_grid() {
  grid_edges_ = edges_.size();
  grid_.init(lo_, hi_, static_cast<int>(edges_.size()), aspect_);
  for (int id = 0; id < static_cast<int>(edges_.size()); ++id)
    if (edges_[id].alive) grid_.insert(id, fm_.uv[edges_[id].a], fm_.uv[edges_[id].b]);
}

void Front::gather(const Vec2& lo, const Vec2& hi) {
  box_lo_ = lo;
  box_hi_ = hi;
  ++visit_;
  near_edges_.clear();
  near_nodes_.clear();
  grid_.query(
      lo, hi, [&](int e) { return ++work_, edges_[e].alive; },
      [&](int e) {
        if (stamp_[e] == visit_) return;
        stamp_[e] = visit_;
        near_edges_.push_back(e);
      });
  if (node_stamp_.size() < fm_.uv.size()) node_stamp_.resize(fm_.uv.size() + 1024, 0);
  for (int ei : near_edges_)
    for (int k : {edges_[ei].a, edges_[ei].b})
      if (node_stamp_[k] != visit_) {
        node_stamp_[k] = visit_;
        near_nodes_.push_back(k);
      }
}

}  // namespace sizemesh::detail
