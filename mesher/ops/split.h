// Split of long edges: an inner edge too long for the size map (the length
// questions of SizeField, core/size_field.h), or too far off the surface, or
// turning too much along it (SplitBounds), gets a node at its uv midpoint and
// its two triangles become four. long_edges() finds the candidates, worst
// first; check_split decides each, apply_split makes it.
#pragma once

#include <array>
#include <vector>

#include "mesher/ops/local_mesh.h"

namespace sizemesh {

// What makes an inner edge too long besides 1.4 sizes (SizeField::kSplitAbove;
// 0: no bound).
struct SplitBounds {
  double deviation = 0;  // its middle further than this off the surface
  // The angle (radians) it may turn along the surface, phi_c: over 1.1 sizes
  // long and turning by more than 1.25 max_turn.
  double max_turn = 0;
  // The size map's floor (h_min): no split for turning leaves an edge under
  // it (a radius under h_min / phi_c turns every edge by more than phi_c).
  double h_floor = 0;
};

namespace ops {

// An edge to split: (T[k], T[k + 1]) of triangle t.
struct LongEdge {
  double excess;  // over 1: by length (in kSplitAbove sizes), off the surface (in d) or turning
  int t, k;
  bool off_surface;  // the excess is the distance from the surface (deviation or turn), not the length
};

// The inner edges too long (split_long_edges), worst first (then by
// triangle and side). nbr: the triangles' neighbours (neighbours()).
std::vector<LongEdge> long_edges(const FaceMesh& fm, const FaceSurface& fs, const SplitBounds& bounds,
                                 const std::vector<std::array<int, 3>>& nbr);

// May edge l be split: t1 = l.t and t2 across the edge both untouched this
// round, the midpoint evaluable on the surface, and the four triangles
// (a, m, c), (m, b, c), (b, m, d), (m, a, d) valid with no angle below both
// the split's floor and the smallest of the pair they replace.
struct SplitCheck {
  bool ok = false;
  int t2 = -1;
  int a = -1, b = -1, c = -1, d = -1;  // the edge (a, b), c opposite in t1, d in t2
  Vec2 uv;                             // the new node
  SurfaceSample sm;
};
SplitCheck check_split(const FaceMesh& fm, FaceSurface& fs, const std::vector<std::array<int, 3>>& nbr,
                       const std::vector<char>& touched, const LongEdge& l);

// The split check_split allowed: the node m at c.uv, t1 and t2 become
// (a, m, c) and (b, m, d), (m, b, c) and (m, a, d) are added; both touched.
void apply_split(FaceMesh& fm, std::vector<char>& touched, int t1, const SplitCheck& c);

// One round of splits of edges inside the face that are too long: longer
// than kSplitAbove times the size wanted along them (the geometric mean of
// their ends' sizes), or, under a deviation bound d > 0, with their middle or
// (for the longest edge of a triangle) the triangle's centre further than d
// from the surface at the same uv, or, with max_turn > 0, over kTurnSplitAbove
// sizes long and turning along the surface by more than kTurnSlack max_turn
// (a chord of length l whose middle lies s off the surface turns by about
// 8 s / l; the constants are SizeField's). Where the front closed on a far
// node the surface lies furthest from the mesh: a chord's height grows with
// its square. Each edge gets a node at its uv midpoint and its two triangles
// become four, kept only if all four are valid and none has an angle below
// both 20 degrees (15 for a chord off the surface) and the smallest of the
// pair it replaces. Worst edges first, each triangle split once per round.
// nbr: the triangles' neighbours (neighbours()) on entry. Returns the splits.
int split_long_edges(FaceMesh& fm, FaceSurface& fs, const SplitBounds& bounds,
                     const std::vector<std::array<int, 3>>& nbr);

}  // namespace ops
}  // namespace sizemesh
