// After the front: thin triangles moved or merged away, back-to-back pairs dropped, doubly meshed edges flipped.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <vector>

#include "core/predicates.h"
#include "core/size_field.h"
#include "mesher/face_mesh.h"
#include "mesher/face_surface.h"
#include "mesher/mesh_surface.h"
#include "mesher/optimise.h"
#include "tests/distorted_rectangle.h"

using namespace sizemesh;
using test::DistortedRectangle;

namespace {

// A hand-made mesh of face 1 on fs: nodes at the surface's uv, the first
// `boundary` of them on the boundary (their global ids 0, 1, ...) in one
// loop, the rest inside; and the given triangles.
FaceMesh hand_mesh(FaceSurface& fs, const std::vector<Vec2>& surface_uv, int boundary,
                   std::vector<std::array<int, 3>> tris) {
  FaceMesh fm;
  fm.face = 1;
  fm.loops.emplace_back();
  for (int k = 0; k < static_cast<int>(surface_uv.size()); ++k) {
    const Vec2 uv = fs.to_mesher(surface_uv[k]);
    fm.add_node(uv, fs.eval(uv), k < boundary ? k : -1);
    if (k < boundary) fm.loops[0].push_back(k);
  }
  fm.tris = std::move(tris);
  return fm;
}

}  // namespace

TEST_CASE("a node left far off a short boundary edge is moved until no thin triangle is left", "[mesher]") {
  // A 10 x 10 square with a boundary node halfway along its bottom side and
  // one inner node near the bottom right corner, fanned to the boundary:
  // three of the five triangles are under 12 degrees.
  const DistortedRectangle square(10.0, 10.0);
  const UniformSize h(5.0);
  FaceSurface fs(square, h, 1);
  FaceMesh fm = hand_mesh(fs, {{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}, {0.95, 0.08}}, 5,
                          {{0, 1, 5}, {1, 2, 5}, {2, 3, 5}, {3, 4, 5}, {4, 0, 5}});
  const std::vector<Vec2> uv = fm.uv;
  auto thin = [&] {
    int n = 0;
    for (const auto& t : fm.tris) n += min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p) < 12;
    return n;
  };
  REQUIRE(thin() == 3);
  CHECK(rescue_thin_triangles(fm, fs) == 1);
  CHECK(thin() == 0);
  for (int k = 0; k < 5; ++k) CHECK(fm.uv[k] == uv[k]);  // the boundary stays
  for (const auto& t : fm.tris) CHECK(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
  CHECK((fm.s[5].p - square.eval_face(1, fs.to_surface(fm.uv[5])).p).norm() <= 1e-12);
  CHECK(rescue_thin_triangles(fm, fs) == 0);  // nothing under 15 degrees is left to move
}

TEST_CASE("two inner nodes left too close together are merged, and the two slivers between them go", "[mesher]") {
  // A 10 x 10 square fanned around two inner nodes 0.2 apart at its centre:
  // the triangles on the short side between them are under 3 degrees. Once
  // merged, the four triangles left are right-angled isosceles, give or take.
  const DistortedRectangle square(10.0, 10.0);
  const UniformSize h(5.0);
  FaceSurface fs(square, h, 1);
  std::vector<Vec2> at;  // the surface's uv of the corners and the two inner nodes
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 10, 0), Vec3(0, 10, 0), Vec3(5, 5, 0), Vec3(5.2, 5, 0)}) {
    at.emplace_back(0.5, 0.5);
    REQUIRE(square.project_to_face(1, p, at.back()));
  }
  FaceMesh fm = hand_mesh(fs, at, 4, {{0, 1, 5}, {1, 2, 5}, {2, 3, 4}, {3, 0, 4}, {0, 5, 4}, {2, 4, 5}});
  const std::vector<Vec2> uv = fm.uv;
  auto smallest = [&] {
    double a = 180;
    for (const auto& t : fm.tris) a = std::min(a, min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p));
    return a;
  };
  for (const auto& t : fm.tris) REQUIRE(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
  REQUIRE(smallest() < 3);
  CHECK(collapse_thin_triangles(fm, fs) == 1);
  CHECK(fm.num_nodes() == 5);
  CHECK(fm.tris.size() == 4);
  CHECK(smallest() > 40);
  for (int k = 0; k < 4; ++k) CHECK(fm.uv[k] == uv[k]);  // the boundary stays, numbered as before
  CHECK(fm.loops == std::vector<std::vector<int>>{{0, 1, 2, 3}});
  for (const auto& t : fm.tris) {
    CHECK(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
    for (int v : t) CHECK((v >= 0 && v < fm.num_nodes()));
  }
  CHECK(collapse_thin_triangles(fm, fs) == 0);
}

TEST_CASE("a pair of triangles on the same nodes facing apart is dropped, and every other triangle stays") {
  // A closed tetrahedron with a fin on its edge 0-1: the fin's two sides are
  // one triangle each on nodes 0, 1, 4, facing apart (two faces back to back,
  // no thickness). Edge 0-1 is used four times until the pair goes.
  SurfaceMesh m;
  m.xyz = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0.5, -1, 0)};
  m.tris = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 1, 4}, {1, 0, 4}};
  m.tri_face = {1, 1, 1, 1, 2, 3};
  m.tri_uv.assign(m.tris.size(), {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)});
  drop_back_to_back(m);
  CHECK(m.stats.back_to_back_dropped == 2);
  REQUIRE(m.tris.size() == 4);
  REQUIRE(m.tri_face.size() == 4);
  REQUIRE(m.tri_uv.size() == 4);
  for (int f : m.tri_face) CHECK(f == 1);
  CHECK(m.xyz.size() == 5);  // node ids unchanged
  // The same triangle twice in one orientation is no fin: both stay.
  m.tris.push_back(m.tris[0]);
  m.tri_face.push_back(1);
  m.tri_uv.push_back(m.tri_uv[0]);
  drop_back_to_back(m);
  CHECK(m.stats.back_to_back_dropped == 0);
  CHECK(m.tris.size() == 5);
}

TEST_CASE("an inner edge two faces both mesh between the same curve nodes is flipped in one of them") {
  // Faces 1 and 2 meet along the curves through a = 0 and b = 1 (a thin
  // strut's sides near its tip): face 1 meshes the quad a, d, b, c with the
  // diagonal a-b, and so does face 2 with the quad a, e, b, f just above it.
  // Edge a-b is used four times until face 1 takes the diagonal c-d.
  SurfaceMesh m;
  m.xyz = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0), Vec3(0.5, 1, 0.1), Vec3(0.5, -1, 0.1)};
  m.tris = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}, {0, 1, 5}};
  m.tri_face = {1, 1, 2, 2};
  for (const auto& t : m.tris) m.tri_uv.push_back({m.xyz[t[0]].head<2>(), m.xyz[t[1]].head<2>(), m.xyz[t[2]].head<2>()});
  flip_shared_inner_edges(m);
  CHECK(m.stats.shared_edges_flipped == 1);
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  CHECK(uses[{0, 1}] == 2);
  CHECK(uses[{2, 3}] == 2);
  // Face 1's triangles keep their side (normal +z) and their uv follow their nodes.
  for (size_t t = 0; t < 2; ++t) {
    const auto& n = m.tris[t];
    CHECK((m.xyz[n[1]] - m.xyz[n[0]]).cross(m.xyz[n[2]] - m.xyz[n[0]]).z() > 0);
    for (int k = 0; k < 3; ++k) CHECK((m.tri_uv[t][k] - m.xyz[n[k]].head<2>()).norm() == 0);
  }
  CHECK(m.tri_face[0] == 1);
  CHECK(m.tri_face[1] == 1);
}
