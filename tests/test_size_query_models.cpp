// Shared models: the walk answers like brute force, exactly at background vertices, and clamps outside points inwards.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "sizing/size_query.h"
#include "tests/size_query_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::Case;
using test::make_case;
using test::proper;
using test::same;
using test::sample;

namespace {

// Every model in the shared directory, loaded once per test process.
const std::vector<Case>& shared_cases() {
  static const std::vector<Case> cases = [] {
    std::vector<Case> out;
    for (const auto& m : test::shared_models()) out.push_back(make_case(m.file, load_model(test::model_path(m.file))));
    return out;
  }();
  return cases;
}

// True when uv lies in (or on) local triangle t of the patch.
bool contains(const FacePatch& patch, int t, const Vec2& p) {
  const auto& v = patch.tris[t];
  for (int k = 0; k < 3; ++k) {
    const Vec2 &P = patch.uv[v[(k + 1) % 3]], &Q = patch.uv[v[(k + 2) % 3]];
    const Vec2 d = Q - P;
    if (d.x() * (p.y() - P.y()) - d.y() * (p.x() - P.x()) < -1e-12 * d.squaredNorm()) return false;
  }
  return true;
}

}  // namespace

// One test case for the shared models, so that they are loaded once per run.
TEST_CASE("on every shared model the walk-through search answers like brute force", "[size_query]") {
  REQUIRE(shared_cases().size() == test::shared_models().size());

  SECTION("random points inside every face, from random hints and from none, give the brute-force answer") {
    std::mt19937 rng(12345);
    size_t total = 0, checked_faces = 0;
    for (const Case& c : shared_cases()) {
      INFO("model " << c.name);
      const SizeQuery query(c.bg, c.h, c.period_u, c.period_v);
      QueryStats st;
      int mismatches = 0, overlaps = 0;
      std::ostringstream log;
      for (const FacePatch& patch : c.bg.patches) {
        const int nt = static_cast<int>(patch.tris.size());
        if (nt == 0) continue;
        ++checked_faces;
        std::uniform_int_distribution<int> pick(0, nt - 1);
        const int samples = std::min(40, 4 + nt / 4);
        for (int i = 0; i < samples; ++i) {
          const int t = pick(rng);
          if (!proper(patch, t)) continue;
          const Vec2 p = sample(patch, t, rng);
          const SizeQuery::Hit ref = query.locate_brute_force(patch.face, p);
          for (int hint : {pick(rng), -1}) {
            const SizeQuery::Hit hit = query.locate(patch.face, p, hint, &st);
            ++total;
            if (same(hit, ref)) continue;
            // A folded uv patch can hold the point in two triangles: both answers are right.
            if (contains(patch, hit.tri, p) && contains(patch, ref.tri, p)) {
              ++overlaps;
              continue;
            }
            if (++mismatches <= 10)
              log << "face " << patch.face << " uv " << p.transpose() << " walk tri " << hit.tri << " h " << hit.h
                  << " brute tri " << ref.tri << " h " << ref.h << "\n";
          }
        }
      }
      INFO(log.str());
      CHECK(mismatches == 0);
      CHECK(overlaps <= static_cast<int>(st.queries / 1000));
      CHECK(st.fallbacks <= st.queries / 100);  // the scan stays the exception
      WARN(c.name << ": " << st.queries << " queries inside faces, mean visited " << st.mean_visited() << ", max "
                  << st.max_visited << ", fallbacks " << st.fallbacks << ", folded-patch double hits " << overlaps);
    }
    CHECK(total > 10000);
    CHECK(checked_faces > 800);
  }

  SECTION("the size at a background vertex's uv equals that vertex's size") {
    for (const Case& c : shared_cases()) {
      INFO("model " << c.name);
      const SizeQuery query(c.bg, c.h, c.period_u, c.period_v);
      int wrong = 0, n = 0;
      std::ostringstream log;
      for (const FacePatch& patch : c.bg.patches) {
        if (patch.tris.empty()) continue;
        int hint = -1;
        for (size_t l = 0; l < patch.uv.size(); ++l) {
          const double want = c.h[patch.vertex[l]];
          const double got = query.at(patch.face, patch.uv[l], hint);
          ++n;
          if (std::abs(got - want) > 1e-12 * want && ++wrong <= 10)
            log << "face " << patch.face << " local vertex " << l << " want " << want << " got " << got << "\n";
        }
      }
      INFO(log.str());
      CHECK(wrong == 0);
      CHECK(query.stats().queries == static_cast<uint64_t>(n));
    }
  }

  SECTION("points pushed outside a face's uv domain get the size at its nearest boundary point") {
    std::mt19937 rng(777);
    std::uniform_real_distribution<double> U(0.2, 0.8);
    for (const Case& c : shared_cases()) {
      INFO("model " << c.name);
      // No periods: a push across a seam must clamp, not wrap.
      const SizeQuery query(c.bg, c.h);
      QueryStats st;
      int n = 0, bad = 0;
      std::ostringstream log;
      for (const FacePatch& patch : c.bg.patches) {
        if (patch.tris.empty()) continue;
        Vec2 lo_uv = patch.uv[0], hi_uv = lo_uv;
        for (const Vec2& uv : patch.uv) {
          lo_uv = lo_uv.cwiseMin(uv);
          hi_uv = hi_uv.cwiseMax(uv);
        }
        const double diag = (hi_uv - lo_uv).norm();
        int used = 0;
        for (int t = 0; t < static_cast<int>(patch.tris.size()) && used < 8; ++t) {
          if (!proper(patch, t)) continue;
          for (int k = 0; k < 3; ++k) {
            if (patch.adj[t][k] >= 0) continue;
            const int a = patch.tris[t][(k + 1) % 3], b = patch.tris[t][(k + 2) % 3];
            const Vec2 P = patch.uv[a], Q = patch.uv[b], d = Q - P;
            const double len = d.norm();
            if (!(len > 0)) continue;
            const Vec2 out(d.y() / len, -d.x() / len);  // right of P->Q: outside a counter-clockwise triangle
            const double s = U(rng);
            const double lo = std::min(c.h[patch.vertex[a]], c.h[patch.vertex[b]]);
            const double hi = std::max(c.h[patch.vertex[a]], c.h[patch.vertex[b]]);
            // Slightly outside (round-off, trimming tolerance, sagitta): within the edge's sizes
            // unless another boundary edge is nearer (then as brute force). Far outside: as brute force.
            for (double push : {1e-12 * len, 1e-7 * len, 1e-3 * len, 0.3 * len, 0.3 * diag}) {
              const Vec2 p = P + s * d + push * out;
              for (int hint : {-1, t}) {
                SizeQuery::Hit hit{0, -1};
                REQUIRE_NOTHROW(hit = query.locate(patch.face, p, hint, &st));
                ++n;
                const SizeQuery::Hit ref = query.locate_brute_force(patch.face, p);
                const bool on_edge = hit.h >= lo * (1 - 1e-12) && hit.h <= hi * (1 + 1e-12);
                const bool as_brute = std::abs(ref.h - hit.h) <= 1e-9 * hi;
                if ((push < 0.01 * len ? on_edge || as_brute : as_brute)) continue;
                if (++bad <= 10)
                  log << "face " << patch.face << " tri " << t << " push " << push / len << " edge lengths, uv "
                      << p.transpose() << " got " << hit.h << " (tri " << hit.tri << ") edge sizes [" << lo << ", " << hi
                      << "], brute " << ref.h << " (tri " << ref.tri << ")\n";
              }
            }
            ++used;
          }
        }
      }
      INFO(log.str());
      CHECK(bad == 0);
      CHECK(st.outside > static_cast<uint64_t>(n) / 2);
      CHECK(st.fallbacks <= st.queries / 100);
      WARN(c.name << ": " << n << " queries outside or across the boundary, outside " << st.outside << ", fallbacks "
                  << st.fallbacks << ", mean visited " << st.mean_visited());
    }
  }
}
