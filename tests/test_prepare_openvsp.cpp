// OpenVSP exports prepared: blunt trailing edges, one-piece skins and fins, a line-ended fuselage, struts; all close.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cad/model.h"
#include "tests/prepare_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::total_area;

namespace {

// A model of tests/data sewn and repaired, without the union (what --info
// describes).
Model described(const std::string& file) {
  LoadOptions o;
  o.describe_only = true;
  return load_model(test::model_path(file), o);
}

}  // namespace

TEST_CASE("OpenVSP's blunt-trailing-edge wing keeps both skins and loses its planform plane", "[models]") {
  // One B-spline skin (root and tip caps, blunt trailing edge, both sides)
  // pinched at its caps' chords, and a planform plane on those chords: the
  // skin's upper half, its lower half and the plane all close the wing two
  // by two. The plane is what lies inside.
  const Model raw = load_model(test::model_path("wing_blunt_te_openvsp.stp"), test::load_options(true, false));
  REQUIRE(raw.num_faces() == 2);
  const double skin = std::max(raw.face_area(1), raw.face_area(2));
  const double plane = std::min(raw.face_area(1), raw.face_area(2));
  const Model model = load_model(test::model_path("wing_blunt_te_openvsp.stp"));
  const Preparation& p = model.info().preparation;
  CHECK(p.components_repaired == 1);
  CHECK(p.internal_faces_removed == 1);
  CHECK(model.closed());
  // The skin's area, integrated over its pieces rather than over the one
  // surface whose caps collapse (2% apart); one skin half and the plane
  // would be 5% short of it.
  CHECK(total_area(model) == Approx(skin).epsilon(0.03));
  CHECK(total_area(model) > 2 * plane);
  // Both halves of the skin, above and below the plane.
  double z_lo = 0, z_hi = 0;
  for (int f = 1; f <= model.num_faces(); ++f) {
    const UVBox box = model.face_uv_bounds(f);
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const Vec3 q = model.eval_face(f, box.lo + Vec2(i / 8.0, j / 8.0).cwiseProduct(box.hi - box.lo)).p;
        z_lo = std::min(z_lo, q.z());
        z_hi = std::max(z_hi, q.z());
      }
  }
  CHECK(z_lo < -0.15);
  CHECK(z_hi > 0.15);
}

TEST_CASE("OpenVSP's one-piece surfaces: a fin that is one face, its caps folded onto the chord, closes", "[models]") {
  // OpenVSP 3.15 without split surfaces writes each component as one
  // B-spline face whose root and tip caps collapse onto the chord line: the
  // fin comes out of sewing as a single face with two free curves, each
  // running out to the leading edge and back along itself. Cut at the turn,
  // its halves sew into a closed body; the planform plane inside it goes.
  const Model model = described("b777_onepiece_openvsp.stp");
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 7);
  const Component& fin = p.components[5];
  CHECK(fin.faces == 1);
  CHECK(fin.free_curves == 2);
  CHECK(fin.role == "solid");
  CHECK(p.components[6].role == "internal");  // the fin's planform plane
  CHECK(p.components[2].role == "internal");  // the wing's
  for (size_t k : {0, 1, 3, 4}) CHECK(p.components[k].role == "solid");
}

TEST_CASE("OpenVSP's one-piece skins, closed round their trailing edge without a period, wrap there", "[models]") {
  // Each skin's B-spline runs from the trailing edge round the leading edge
  // back to it, its two ends one seam edge, but the surface is not periodic:
  // what a cut across that seam sees beyond the parameter range is the
  // surface from its other end.
  const Model model = described("b777_onepiece_openvsp.stp");
  const double diag = (model.info().bbox_max - model.info().bbox_min).norm();
  int wrapped = 0;
  for (int f = 1; f <= model.num_faces(); ++f) {
    CHECK(model.face_wrap_u(f) == model.face_period_u(f));
    if (model.face_period_v(f) > 0 || !(model.face_wrap_v(f) > 0)) {
      CHECK(model.face_wrap_v(f) == model.face_period_v(f));
      continue;
    }
    ++wrapped;
    const UVBox box = model.face_uv_bounds(f);
    const double w = model.face_wrap_v(f);
    CHECK(w == Approx(box.hi.y() - box.lo.y()).epsilon(1e-9));
    for (double su : {0.2, 0.5, 0.8}) {
      const double u = box.lo.x() + su * (box.hi.x() - box.lo.x());
      // The two sides of the seam are one curve.
      CHECK((model.eval_face(f, Vec2(u, box.lo.y())).p - model.eval_face(f, Vec2(u, box.hi.y())).p).norm() <
            1e-6 * diag);
      for (double sv : {0.1, 0.3, 0.7}) {
        const Vec3 p = model.eval_face(f, Vec2(u, box.lo.y() + sv * w)).p;
        CHECK((model.eval_face(f, Vec2(u, box.lo.y() + (sv + 1) * w)).p - p).norm() < 1e-9 * diag);
        CHECK((model.eval_face(f, Vec2(u, box.lo.y() + (sv - 1) * w)).p - p).norm() < 1e-9 * diag);
      }
    }
  }
  CHECK(wrapped == 3);  // the tail's two skins and the fuselage; the rest split at their folds
}

TEST_CASE("OpenVSP's one-piece fin: its caps, halves folded onto the chord, become flat faces with no point-like curve", "[models]") {
  // The fin of this export is one skin and one cap face per end; cut at the
  // caps' turn, each cap half is a B-spline ruled between the chord line and
  // the airfoil, collapsing at both ends of the chord into curves of zero
  // length that the front cannot start from. Flat, they are rebuilt on their
  // plane without those curves.
  const Model model = load_model(test::model_path("b777_nosplit_openvsp.stp"));
  const Preparation& p = model.info().preparation;
  CHECK(p.faces_made_planar >= 4);
  CHECK(model.closed());
  int point_like = 0;
  for (int f = 1; f <= model.num_faces(); ++f)
    for (const FaceLoop& loop : model.face_loops(f))
      for (const CurveUse& c : loop)
        if (!model.curve_degenerated(c.curve) && model.curve_length(c.curve) <= 1e-9 * model.info().diagonal()) {
          INFO("face " << f << " curve " << c.curve);
          ++point_like;
        }
  CHECK(point_like == 0);
}

TEST_CASE("OpenVSP's fuselage ending in a vertical line flagged as a point: a real edge there, opened at its folds and sewn", "[models]") {
  // The 777's fuselage ends at x = 206.5 ft in a section of zero width and
  // 3.8 ft height: the surface maps the end's degenerated edge (a point, as
  // written) onto that line, up it and back down. Meshed as a point, every
  // node along the line fell onto one vertex: flat fans and turned-over
  // triangles at the tail. Made a real edge on the line and split at its
  // two turns, its pieces sew into one closed fuselage (the union's budget
  // pinned, so that its route does not depend on the machine's load).
  LoadOptions generous;
  generous.union_seconds = 60;
  const Model model = load_model(test::model_path("b777_nosplit_openvsp.stp"), generous);
  const double tol = LoadOptions{}.sewing_tolerance_rel * model.info().diagonal();
  int line_like = 0, at_end = 0;
  for (int f = 1; f <= model.num_faces(); ++f)
    for (const FaceLoop& loop : model.face_loops(f))
      for (const CurveUse& u : loop) {
        double t0, t1;
        model.curve_range(u.curve, t0, t1);
        if (model.curve_degenerated(u.curve)) {
          Eigen::AlignedBox3d image;
          for (int k = 0; k <= 16; ++k) image.extend(model.eval_face(f, model.eval_pcurve(u.curve, f, u.side, t0 + (t1 - t0) * k / 16)).p);
          line_like += image.diagonal().norm() > 100 * tol;
        } else {
          const Vec3 a = model.eval_curve(u.curve, t0), b = model.eval_curve(u.curve, t1);
          at_end += std::abs(a.x() - 206.5) < 1e-3 && std::abs(b.x() - 206.5) < 1e-3 && std::abs(a.z() - b.z()) > 0.5;
        }
      }
  CHECK(line_like == 0);
  CHECK(model.info().preparation.edges_made_real == 1);
  CHECK(at_end >= 4);  // the line's pieces, on either side of the fold
  for (const auto& c : model.info().preparation.components)
    if (c.role == "solid" && c.bbox_max.x() > 206 && c.bbox_min.x() < 1) CHECK(c.route.rfind("B-rep union", 0) == 0);
}

TEST_CASE("OpenVSP's truss-braced wing: the struts' skins, pinched at their tips, stay, and the planes and caps inside go", "[models]") {
  // Component 1 is a pod with a strut sewn at each side. Each half of the
  // pod is one skin whose root and tip caps are built in: flat strips folded
  // onto the chord, the root caps of the two halves back to back on y = 0,
  // each tip cap back to back with its strut's root cap. Split off at the
  // crease, each cap's end (its section collapsed onto the chord, run from
  // the trailing edge to the leading edge and back) splits it in two at the
  // leading edge: six caps in halves, found as six coincident pairs, go with
  // the four planform planes. Each strut is one skin, pinched to a line at
  // its tip (the two sides of its boundary run along the same line with
  // different parametrisations), and a planform plane. Split at the pinch, a
  // strut's skin closes over its tip.
  const Model model = described("tbw_sugar_openvsp.stp");
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 7);
  const Component& pod = p.components[0];
  CHECK(pod.faces == 8);
  CHECK(pod.bbox_max.y() == Approx(48.915).margin(0.01));
  CHECK(pod.role == "solid");
  CHECK(pod.faces_removed == 16);
  // The main wing and the horizontal tail: each half's skin carries its
  // root cap, and the halves' caps lie back to back on y = 0. Their
  // trailing-edge spans collapse to a point in every section (no normal
  // there), so the crease is judged where a normal exists; the collapsed
  // strips are dropped from the pieces. Both root caps go, in halves, with
  // the two planform planes: one closed shell over both halves.
  for (int k : {1, 2}) {
    CHECK(p.components[k].role == "solid");
    CHECK(p.components[k].faces_removed == 6);
  }
  CHECK(p.duplicate_faces_removed == 20);
  for (const Component& c : p.components) CHECK(c.role == "solid");
  // Every face taken out of any component lies inside one of the solids.
  CHECK(p.internal_faces_removed == 11);
  // The aircraft is symmetric in y: the pod's two halves, the struts' and
  // the wing's, tail's and fin's skins, each with its tip cap in two halves
  // split at its leading edge, each jury strut split at its pinch, the fin's
  // two sides and the fuselage.
  CHECK(model.num_faces() == 27);
  // The area on each side, summed over a uv grid (the faces are untrimmed
  // patches; the fuselage is one face across both sides), what lies on
  // y = 0 on neither side; and each face's centroid.
  double left = 0, right = 0, middle = 0;
  std::map<int, std::pair<double, Vec3>> pieces;  // per face as read: area, moment
  constexpr int n = 64;
  for (int f = 1; f <= model.num_faces(); ++f) {
    const UVBox b = model.face_uv_bounds(f);
    const Vec2 step = (b.hi - b.lo) / n;
    double area = 0;
    Vec3 moment = Vec3::Zero();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const SurfaceD1 d = model.eval_face(f, b.lo + Vec2((i + 0.5) * step.x(), (j + 0.5) * step.y()));
        const double a = d.du.cross(d.dv).norm() * step.x() * step.y();
        (std::abs(d.p.y()) < 1e-6 ? middle : d.p.y() < 0 ? left : right) += a;
        area += a, moment += a * d.p;
      }
    auto& [a, m] = pieces.emplace(model.source_face(f), std::make_pair(0.0, Vec3(Vec3::Zero()))).first->second;
    a += area, m += moment;
  }
  // The pieces of each face as read, taken together, have a mirror twin
  // (the jury struts' halves, split at a pinch chosen on each side alone,
  // need not).
  REQUIRE(pieces.size() == 12);
  int twins = 0;
  for (const auto& [face, am] : pieces) {
    const double area = am.first;
    const Vec3 c = am.second / area, mirror(c.x(), -c.y(), c.z());
    twins += std::any_of(pieces.begin(), pieces.end(), [&](const auto& g) {
      return std::abs(g.second.first - area) < 1e-3 * area &&
             (g.second.second / g.second.first - mirror).norm() < 1e-3 * std::sqrt(area);
    });
  }
  CHECK(twins == 12);
  CHECK(left == Approx(right).epsilon(0.01));
  CHECK(left + right + middle == Approx(total_area(model)).epsilon(0.01));
}

TEST_CASE("the shared OpenVSP aircraft close into one surface", "[models]") {
  for (const char* file : {"f16_openvsp.stp", "manta2_openvsp.stp"}) {
    SECTION(file) {
      const Model raw = load_model(test::model_path(file), test::load_options(true, false));
      // A budget no loaded machine runs out of: this is the B-rep route.
      LoadOptions generous;
      generous.union_seconds = 60;
      const Model model = load_model(test::model_path(file), generous);
      const Preparation& p = model.info().preparation;
      CHECK_FALSE(raw.closed());
      CHECK(p.fused);
      CHECK(p.fallback.empty());
      CHECK(model.closed());
      CHECK(model.info().shells == 1);
      // Every component keeps faces in the result: none is dropped.
      std::vector<int> kept(raw.num_faces() + 1, 0);
      for (int f = 1; f <= model.num_faces(); ++f) ++kept.at(model.source_face(f));
      REQUIRE(p.components.size() >= 6);
      for (const Component& comp : p.components) {
        int n = 0;
        for (int f : comp.face_ids) n += kept.at(f);
        CHECK(n > 0);
      }
      // The union takes area away (the parts inside other components), never adds.
      CHECK(total_area(model) < total_area(raw));
    }
  }
}
