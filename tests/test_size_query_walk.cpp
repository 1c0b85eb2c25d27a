// The walk on hand-made patches ends on degenerate, folded and cyclic uv, goes around holes, and falls back on space.
#include <BRepPrimAPI_MakeBox.hxx>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "cad/occt_model.h"
#include "sizing/size_query.h"

using namespace sizemesh;

namespace {

// Builds a FacePatch with adjacency from uv points and counter-clockwise triangles.
FacePatch patch_from(int face, const std::vector<Vec2>& uv, const std::vector<std::array<int, 3>>& tris, int first_vertex) {
  FacePatch p;
  p.face = face;
  p.uv = uv;
  p.tris = tris;
  for (int i = 0; i < static_cast<int>(uv.size()); ++i) p.vertex.push_back(first_vertex + i);
  p.adj.assign(tris.size(), {-1, -1, -1});
  std::map<std::pair<int, int>, std::pair<int, int>> open;
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      int a = tris[t][(k + 1) % 3], b = tris[t][(k + 2) % 3];
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = open.find(key);
      if (it == open.end()) {
        open[key] = {t, k};
      } else {
        p.adj[t][k] = it->second.first;
        p.adj[it->second.first][it->second.second] = t;
        open.erase(it);
      }
    }
  p.global_tri.assign(tris.size(), -1);
  return p;
}

}  // namespace

TEST_CASE("the walk terminates on degenerate, folded and cyclic uv patches and on edge and vertex points",
          "[size_query]") {
  // Face 1: a 6x6 grid of unit squares, split into triangles, with a row of
  // zero-area triangles inserted (collinear vertices) and the answer linear.
  BackgroundMesh bg;
  std::vector<Vec2> uv;
  std::vector<std::array<int, 3>> tris;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) uv.emplace_back(i, j);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2) {
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  // A zero-area triangle hanging on the top boundary: (0,n) (1,n) and the midpoint (0.5,n),
  // oriented consistently with its neighbour.
  uv.emplace_back(0.5, n);
  const int mid = static_cast<int>(uv.size()) - 1;
  tris.push_back({id(0, n), id(1, n), mid});
  bg.patches.push_back(patch_from(1, uv, tris, 0));
  // Face 2: no triangles.
  bg.patches.emplace_back();
  bg.patches.back().face = 2;
  // Face 3: a fan whose uv triangulation folds over itself (two triangles flipped).
  std::vector<Vec2> fuv = {{0, 0}, {1, 0}, {0.2, 1}, {-1, 0.3}, {-0.5, -1}, {0.6, -0.8}};
  std::vector<std::array<int, 3>> ftris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1}, {0, 2, 1}};
  bg.patches.push_back(patch_from(3, fuv, ftris, static_cast<int>(uv.size())));
  bg.xyz.resize(uv.size() + fuv.size(), Vec3::Zero());
  std::vector<double> h(bg.xyz.size());
  for (size_t i = 0; i < uv.size(); ++i) h[i] = 1 + uv[i].x() + 2 * uv[i].y();  // linear: exact everywhere
  h[mid] = 1 + 0.5 + 2 * n;
  for (size_t i = 0; i < fuv.size(); ++i) h[uv.size() + i] = 3 + i;
  const SizeQuery query(bg, h);
  auto linear = [](const Vec2& p) { return 1 + p.x() + 2 * p.y(); };

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-0.2, n + 0.2);  // outside by at most 0.2 edge lengths
  std::uniform_int_distribution<int> T(0, static_cast<int>(tris.size()) - 1);
  QueryStats st;
  for (int i = 0; i < 20000; ++i) {
    // Grid points (on edges and vertices) half of the time.
    Vec2 p(U(rng), U(rng));
    if (i % 2) p = Vec2(std::round(p.x() * 2) / 2, std::round(p.y() * 2) / 2);
    const SizeQuery::Hit hit = query.locate(1, p, T(rng), &st);
    const Vec2 q = p.cwiseMax(Vec2::Zero()).cwiseMin(Vec2::Constant(n));  // nearest domain point
    INFO("uv " << p.transpose() << " tri " << hit.tri);
    REQUIRE(hit.h == Approx(linear(q)).epsilon(1e-12));
  }
  CHECK(st.fallbacks == 0);
  CHECK(st.outside > 0);

  // Folded fan: every query ends, inside the convex hull of the corner sizes.
  QueryStats fs;
  std::uniform_real_distribution<double> F(-1.5, 1.5);
  for (int i = 0; i < 5000; ++i) {
    const Vec2 p(F(rng), F(rng));
    const SizeQuery::Hit hit = query.locate(3, p, i % 7 - 1, &fs);
    CHECK(hit.h >= 3 - 1e-12);
    CHECK(hit.h <= 8 + 1e-12);
  }
  CHECK(fs.queries == 5000);

  // Random triangle soups (overlapping, folded, degenerate, non-manifold): every
  // query ends with a convex combination of the sizes.
  for (int soup = 0; soup < 40; ++soup) {
    BackgroundMesh rb;
    std::vector<Vec2> ruv;
    std::uniform_real_distribution<double> R(0, 1);
    const int nv = 6 + soup % 10;
    for (int i = 0; i < nv; ++i)
      ruv.emplace_back(soup % 3 == 0 ? std::round(R(rng) * 4) / 4 : R(rng), R(rng));  // repeated uvs too
    std::vector<std::array<int, 3>> rt;
    for (int i = 0; i < 3 * nv; ++i) {
      std::array<int, 3> t = {static_cast<int>(rng() % nv), static_cast<int>(rng() % nv), static_cast<int>(rng() % nv)};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      const Vec2 e1 = ruv[t[1]] - ruv[t[0]], e2 = ruv[t[2]] - ruv[t[0]];
      if (e1.x() * e2.y() - e1.y() * e2.x() < 0) std::swap(t[1], t[2]);
      rt.push_back(t);
    }
    if (rt.empty()) continue;
    rb.patches.push_back(patch_from(1, ruv, rt, 0));
    rb.xyz.resize(nv, Vec3::Zero());
    std::vector<double> rh(nv);
    for (int i = 0; i < nv; ++i) rh[i] = 1 + i;
    const SizeQuery rq(rb, rh);
    std::uniform_real_distribution<double> P(-0.5, 1.5);
    for (int i = 0; i < 200; ++i) {
      const SizeQuery::Hit hit = rq.locate(1, Vec2(P(rng), P(rng)), static_cast<int>(rng() % (rt.size() + 1)) - 1);
      REQUIRE(hit.h >= 1 - 1e-12);
      REQUIRE(hit.h <= nv + 1e-12);
      REQUIRE(hit.tri >= 0);
      REQUIRE(hit.tri < static_cast<int>(rt.size()));
    }
  }

  int hint = -1;
  CHECK_THROWS_AS(query.at(2, Vec2(0, 0), hint), Error);
  CHECK_THROWS_AS(query.at(4, Vec2(0, 0), hint), Error);
  CHECK_THROWS_AS(query.at(0, Vec2(0, 0), hint), Error);
  CHECK_THROWS_AS(query.at(1, Vec2(NAN, 0), hint), Error);
  CHECK_THROWS_WITH(query.at(2, Vec2(0, 0), hint), Catch::Contains("face 2"));
}

TEST_CASE("given the surface, a face with no background triangles takes the size nearest in space", "[size_query]") {
  Model model = model_from_shape(BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape());
  BackgroundMesh bg = build_background_mesh(model);
  bg.patches[1].tris.clear();  // face 2 as if its tessellation had failed
  bg.patches[1].adj.clear();
  bg.patches[1].global_tri.clear();
  std::vector<double> h(bg.xyz.size());
  for (size_t v = 0; v < h.size(); ++v) h[v] = 0.1 + 0.05 * bg.xyz[v].x() + 0.02 * bg.xyz[v].z();
  SizeQuery query(bg, h);
  int hint = -1;
  CHECK_THROWS_WITH(query.at(2, Vec2(0.5, 0.5), hint), Catch::Contains("face 2"));
  query.set_surface([&model](int face, const Vec2& uv) { return model.eval_face(face, uv).p; });
  const UVBox box = model.face_uv_bounds(2);
  const Vec2 mid = 0.5 * (box.lo + box.hi);
  CHECK(query.at(2, mid, hint) == query.at_xyz(model.eval_face(2, mid).p));
  CHECK_THROWS_AS(query.at(7, mid, hint), Error);  // no such face
}

TEST_CASE("a walk blocked by a hole goes around it, and points in the hole take the size on its boundary",
          "[size_query]") {
  // An 8x8 grid of unit squares without the 2x2 block [3,5]x[3,5]; the size is linear in uv.
  BackgroundMesh bg;
  std::vector<Vec2> uv;
  std::vector<std::array<int, 3>> tris;
  const int n = 8;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) uv.emplace_back(i, j);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i >= 3 && i < 5 && j >= 3 && j < 5) continue;
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  bg.patches.push_back(patch_from(1, uv, tris, 0));
  bg.xyz.resize(uv.size(), Vec3::Zero());
  auto linear = [](const Vec2& p) { return 2 + 0.5 * p.x() + 3 * p.y(); };
  std::vector<double> h(uv.size());
  for (size_t i = 0; i < uv.size(); ++i) h[i] = linear(uv[i]);
  const SizeQuery query(bg, h);
  // Nearest point of the domain: clamp into the square, then out of the hole.
  auto nearest = [&](Vec2 p) {
    p = p.cwiseMax(Vec2::Zero()).cwiseMin(Vec2::Constant(n));
    if (p.x() > 3 && p.x() < 5 && p.y() > 3 && p.y() < 5) {
      const double d[4] = {p.x() - 3, 5 - p.x(), p.y() - 3, 5 - p.y()};
      const int k = static_cast<int>(std::min_element(d, d + 4) - d);
      if (k == 0) p.x() = 3;
      if (k == 1) p.x() = 5;
      if (k == 2) p.y() = 3;
      if (k == 3) p.y() = 5;
    }
    return p;
  };
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(-0.3, n + 0.3);
  std::uniform_int_distribution<int> T(0, static_cast<int>(tris.size()) - 1);
  QueryStats st;
  int in_hole = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec2 p(U(rng), U(rng));
    in_hole += p.x() > 3 && p.x() < 5 && p.y() > 3 && p.y() < 5;
    const SizeQuery::Hit hit = query.locate(1, p, T(rng), &st);
    INFO("uv " << p.transpose() << " tri " << hit.tri);
    REQUIRE(hit.h == Approx(linear(nearest(p))).epsilon(1e-12));
  }
  CHECK(in_hole > 500);
  CHECK(st.fallbacks == 0);
  CHECK(st.outside > 0);
}
