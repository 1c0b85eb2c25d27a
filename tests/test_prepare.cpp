// Geometry preparation (cad/prepare): shapes built with OCCT whose
// wetted surface is known exactly: a box wing through a cylinder fuselage,
// two touching boxes, and a wing made of two open halves with an internal
// planform plane; the shared OpenVSP aircraft close into one surface.
#include <catch2/catch.hpp>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopExp.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "cad/occt_model.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "sizing/params.h"
#include "core/size_field.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

TopoDS_Compound compound(std::initializer_list<TopoDS_Shape> parts) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& s : parts) b.Add(c, s);
  return c;
}

// Planar face through four corners.
TopoDS_Shape quad(gp_Pnt a, gp_Pnt b, gp_Pnt c, gp_Pnt d) {
  return BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire(), true).Face();
}

double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (const auto& t : m.tris) v += m.xyz[t[0]].dot(m.xyz[t[1]].cross(m.xyz[t[2]])) / 6.0;
  return v;
}

double total_area(const Geometry& g) {
  double a = 0;
  for (int f = 1; f <= g.num_faces(); ++f) a += g.face_area(f);
  return a;
}

// Meshes the model at size h: every face, nothing inverted or crossing.
std::pair<SurfaceMesh, MeshQuality> mesh_checked(const Model& model, double h) {
  const UniformSize size(h);
  SurfaceMesh m = mesh_surface(model, size);
  REQUIRE(m.failures.empty());
  MeshQuality q = mesh_quality(m, model, size);
  CHECK(q.inverted == 0);
  CHECK(q.self_intersections == 0);
  return {std::move(m), std::move(q)};
}

// ... and a closed, consistently oriented surface.
SurfaceMesh mesh_closed(const Model& model, double h) {
  auto [m, q] = mesh_checked(model, h);
  CHECK(q.boundary_edges == 0);
  CHECK(q.nonmanifold_edges == 0);
  CHECK(q.orientation_conflicts == 0);
  return m;
}

// A model of tests/data sewn and repaired, without the union (what --info
// describes).
Model described(const std::string& file) {
  LoadOptions o;
  o.describe_only = true;
  return load_model(test::model_path(file), o);
}

// Triangles using each mesh edge.
std::map<std::pair<int, int>, int> edge_uses(const SurfaceMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  return uses;
}

}  // namespace

TEST_CASE("a box wing through a cylinder fuselage unites into one closed surface of the analytic area") {
  // Fuselage: radius 1 along x from 0 to 10. Wing: chord 2 (x 3..5), span 12
  // (y -6..6), thickness 0.4 (z -0.2..0.2).
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape wing = BRepPrimAPI_MakeBox(gp_Pnt(3, -6, -0.2), 2.0, 12.0, 0.4).Shape();
  const Model model = model_from_shape(compound({fuselage, wing}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.fused);
  CHECK(p.solids_fused == 2);
  CHECK(model.closed());
  CHECK(model.info().solids == 1);
  // Cylinder side with two holes, two caps; wing top, bottom, front and back
  // each cut in two by the fuselage, two tips.
  CHECK(model.num_faces() == 13);

  // Exact wetted area: the cylinder without the two strips |z| < 0.2 under
  // the wing, plus the box without what lies inside the cylinder.
  const double s = 0.2, c = std::sqrt(1 - s * s);
  const double cylinder = 2 * kPi * 10 + 2 * kPi - 2 * 2 * (2 * std::asin(s));
  const double box = 2 * (2 * 12 + 2 * 0.4 + 12 * 0.4) - 2 * (2 * 2 * c) - 2 * 2 * (s * c + std::asin(s));
  CHECK(total_area(model) == Approx(cylinder + box).epsilon(1e-3));

  // Junction curves: shared by a face from the fuselage and one from the wing
  // (the sewn ids: the cylinder's three faces come first), four a side.
  std::map<int, std::set<bool>> curve_sides;
  for (int f = 1; f <= model.num_faces(); ++f) {
    const int src = model.source_face(f);
    REQUIRE(src >= 1);
    REQUIRE(src <= 9);
    for (const auto& loop : model.face_loops(f))
      for (const auto& use : loop) curve_sides[use.curve].insert(src <= 3);
  }
  int junctions = 0;
  for (const auto& [curve, sides] : curve_sides) junctions += sides.size() == 2;
  CHECK(junctions == 8);

  const SurfaceMesh m = mesh_closed(model, 0.1);
  const double volume = kPi * 10 + 2 * 12 * 0.4 - 2 * 2 * (s * c + std::asin(s));
  CHECK(signed_volume(m) == Approx(volume).epsilon(5e-3));  // outward, polygonal
}

TEST_CASE("config face ids keep addressing the faces as sewn after the union") {
  const Model model = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                                 BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}));
  std::vector<int> source;
  for (int f = 1; f <= model.num_faces(); ++f) source.push_back(model.source_face(f));
  REQUIRE(model.info().sewn_faces == 12);
  SizingParams p;
  for (int id = 1; id <= 12; ++id) p.face_size[id] = UserSize{0.01 * id, ""};
  p.face_beta[3] = 1.5;
  remap_face_ids(p, source, 12);
  REQUIRE(p.face_size.size() == 10);  // one entry per result face
  for (int f = 1; f <= model.num_faces(); ++f) CHECK(p.face_size.at(f).value == Approx(0.01 * model.source_face(f)));
  for (const auto& [f, beta] : p.face_beta) CHECK(model.source_face(f) == 3);
  SizingParams bad;
  bad.face_mu_d[13] = 2;
  CHECK_THROWS_WITH(remap_face_ids(bad, source, 12), "config names face 13 but the model has 12 faces");
}

TEST_CASE("two touching boxes give one closed surface with no internal face") {
  const Model model = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                                 BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}));
  // Face to face, the two are repaired as one body: the faces at x = 1 go.
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.components[0].faces_removed == 2);
  CHECK(p.components[1].route.rfind("one body with component 1 (faces back to back)", 0) == 0);
  CHECK(model.closed());
  CHECK(model.num_faces() == 10);  // two ends, four sides in two pieces each
  CHECK(total_area(model) == Approx(10.0).epsilon(1e-12));
  const SurfaceMesh m = mesh_closed(model, 0.2);
  CHECK(signed_volume(m) == Approx(2.0).epsilon(1e-9));
  for (const auto& t : m.tris) {
    const bool on_contact = std::abs(m.xyz[t[0]].x() - 1) < 1e-9 && std::abs(m.xyz[t[1]].x() - 1) < 1e-9 &&
                            std::abs(m.xyz[t[2]].x() - 1) < 1e-9;
    CHECK_FALSE(on_contact);
  }
  const Model raw = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                               BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}),
                                     test::load_options(true, false));
  CHECK(raw.num_faces() == 12);
  CHECK_FALSE(raw.info().preparation.fused);
}

TEST_CASE("an internal planform plane between two open wing halves is taken out and the wing closes") {
  // Upper half: z 0..0.2 without its bottom; lower half: z -0.2..0 without
  // its top; the plane z = 0 shares their edges, so each is used three times.
  const double X = 2, Y = 6, t = 0.2;
  std::vector<TopoDS_Shape> faces;
  for (double z : {t, -t}) {
    faces.push_back(quad({0, 0, z}, {X, 0, z}, {X, Y, z}, {0, Y, z}));
    faces.push_back(quad({0, 0, 0}, {X, 0, 0}, {X, 0, z}, {0, 0, z}));
    faces.push_back(quad({0, Y, 0}, {X, Y, 0}, {X, Y, z}, {0, Y, z}));
    faces.push_back(quad({0, 0, 0}, {0, Y, 0}, {0, Y, z}, {0, 0, z}));
    faces.push_back(quad({X, 0, 0}, {X, Y, 0}, {X, Y, z}, {X, 0, z}));
  }
  faces.push_back(quad({0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0}));
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& f : faces) b.Add(c, f);

  const Model raw = model_from_shape(c, test::load_options(true, false));
  CHECK_FALSE(raw.closed());
  const Model model = model_from_shape(c);
  const Preparation& p = model.info().preparation;
  CHECK(p.internal_faces_removed == 1);
  CHECK(p.components_repaired == 1);
  CHECK(model.closed());
  CHECK(model.num_faces() == 10);
  CHECK(total_area(model) == Approx(2 * (X * Y + X * 2 * t + Y * 2 * t)).epsilon(1e-12));
  const SurfaceMesh m = mesh_closed(model, 0.1);
  CHECK(signed_volume(m) == Approx(X * Y * 2 * t).epsilon(1e-9));
}

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

TEST_CASE("a T of two plates is imprinted: the junction curve is shared by three faces, no triangle twice") {
  // Base plate z = 0 (x 0..2, y 0..1); stem plate x = 1 standing on it (z 0..1).
  const TopoDS_Shape base = quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0});
  const TopoDS_Shape stem = quad({1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1});
  const Model model = model_from_shape(compound({base, stem}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.sheets_imprinted == 2);
  CHECK(p.fallback.empty());
  REQUIRE(model.num_faces() == 3);  // the base cut in two along x = 1, the stem
  CHECK(total_area(model) == Approx(3.0).epsilon(1e-12));
  std::map<int, int> uses;
  for (int f = 1; f <= 3; ++f)
    for (const auto& loop : model.face_loops(f))
      for (const auto& use : loop) ++uses[use.curve];
  int junction = 0, on_line = 0;
  for (const auto& [c, n] : uses) {
    if (n != 3) continue;
    ++junction;
    double t0, t1;
    model.curve_range(c, t0, t1);
    for (double t : {t0, 0.5 * (t0 + t1), t1}) {
      const Vec3 x = model.eval_curve(c, t);
      on_line += std::abs(x.x() - 1) < 1e-9 && std::abs(x.z()) < 1e-9;
    }
  }
  CHECK(junction == 1);
  CHECK(on_line == 3);

  const auto [m, q] = mesh_checked(model, 0.1);
  std::set<std::array<int, 3>> seen;
  for (const auto& t : m.tris) {
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    CHECK(seen.insert(key).second);  // no duplicate triangle
  }
  // Mesh edges on the junction are used by three triangles; no other edge is.
  int triple = 0;
  for (const auto& [e, n] : edge_uses(m)) {
    if (n < 3) continue;
    ++triple;
    CHECK(n == 3);
    for (int v : {e.first, e.second}) {
      CHECK(std::abs(m.xyz[v].x() - 1) < 1e-9);
      CHECK(std::abs(m.xyz[v].z()) < 1e-9);
    }
  }
  CHECK(triple >= 10);  // the 1-long junction at h = 0.1
  CHECK(q.nonmanifold_edges == triple);
}

TEST_CASE("a sheet fin standing on a cylinder fuselage is imprinted on it, its part inside dropped") {
  // Fin: the plane y = 0, x 4..6, z 0.5..2, so it enters the fuselage (radius 1).
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape fin = quad({4, 0, 0.5}, {6, 0, 0.5}, {6, 0, 2}, {4, 0, 2});
  const Model model = model_from_shape(compound({fuselage, fin}));
  const Preparation& p = model.info().preparation;
  CHECK(p.sheets_imprinted == 1);
  CHECK(p.sheet_pieces_dropped == 1);
  CHECK(p.fallback.empty());
  // Fuselage area, plus the fin above z = 1 (2 x 1).
  CHECK(total_area(model) == Approx(2 * kPi * 10 + 2 * kPi + 2.0).epsilon(1e-9));
  const auto [m, q] = mesh_checked(model, 0.1);
  // Free edges only on the fin's three outer sides (x = 4, x = 6, z = 2).
  for (const auto& [e, n] : edge_uses(m)) {
    if (n != 1) continue;
    const Vec3 mid = 0.5 * (m.xyz[e.first] + m.xyz[e.second]);
    CHECK(std::abs(mid.y()) < 1e-9);
    CHECK(mid.z() > 1 - 1e-9);
  }
}

TEST_CASE("fuselage, wing through it and sheet fin on it: one surface, exact area, conforming junctions") {
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape wing = BRepPrimAPI_MakeBox(gp_Pnt(3, -6, -0.2), 2.0, 12.0, 0.4).Shape();
  const TopoDS_Shape fin = quad({6, 0, 0.5}, {8, 0, 0.5}, {8, 0, 2.5}, {6, 0, 2.5});
  const Model model = model_from_shape(compound({fuselage, wing, fin}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 3);
  CHECK(p.fused);
  CHECK(p.sheets_imprinted == 1);
  CHECK(p.sheet_pieces_dropped == 1);
  CHECK(p.fallback.empty());
  CHECK(model.num_faces() == 14);  // the 13 of the wing-body union and the fin above z = 1
  const double s = 0.2, c = std::sqrt(1 - s * s);
  const double cylinder = 2 * kPi * 10 + 2 * kPi - 2 * 2 * (2 * std::asin(s));
  const double box = 2 * (2 * 12 + 2 * 0.4 + 12 * 0.4) - 2 * (2 * 2 * c) - 2 * 2 * (s * c + std::asin(s));
  CHECK(total_area(model) == Approx(cylinder + box + 2 * 1.5).epsilon(1e-3));
  const auto [m, q] = mesh_checked(model, 0.1);
  // Watertight but for the fin's three free sides (x = 6, x = 8, z = 2.5);
  // the fin's root on the fuselage is used by three triangles.
  int open = 0, root = 0;
  for (const auto& [e, n] : edge_uses(m)) {
    CHECK(n <= 3);
    if (n == 3) {
      ++root;
      for (int v : {e.first, e.second}) {
        CHECK(std::abs(m.xyz[v].y()) < 1e-9);
        CHECK(std::abs(m.xyz[v].z() - 1) < 1e-9);
      }
    }
    if (n != 1) continue;
    ++open;
    const Vec3 mid = 0.5 * (m.xyz[e.first] + m.xyz[e.second]);
    CHECK(std::abs(mid.y()) < 1e-9);
    CHECK(mid.z() > 1 - 1e-9);
  }
  CHECK(open >= 3 * 10);
  CHECK(root >= 10);
  CHECK(q.nonmanifold_edges == root);
}

TEST_CASE("an open box whose mouth lies flat is capped there and united with the box it reaches out of") {
  // A: the unit cube. B: a box x 0.5..1.5, y and z 0.25..0.75, without its
  // face at x = 1.5, so it reaches out of A through A's face x = 1. Its free
  // curves are one flat loop: a planar cap closes it (an OpenVSP tip or strut
  // root exported without its cap), and the union keeps what lies outside A.
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape();
  const double x0 = 0.5, x1 = 1.5, lo = 0.25, hi = 0.75;
  const TopoDS_Shape b = compound({quad({x0, lo, lo}, {x0, hi, lo}, {x0, hi, hi}, {x0, lo, hi}),
                                   quad({x0, lo, lo}, {x1, lo, lo}, {x1, hi, lo}, {x0, hi, lo}),
                                   quad({x0, lo, hi}, {x1, lo, hi}, {x1, hi, hi}, {x0, hi, hi}),
                                   quad({x0, lo, lo}, {x1, lo, lo}, {x1, lo, hi}, {x0, lo, hi}),
                                   quad({x0, hi, lo}, {x1, hi, lo}, {x1, hi, hi}, {x0, hi, hi})});
  const Model model = model_from_shape(compound({a, b}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.components[0].role == "solid");
  CHECK(p.components[1].role == "solid");
  CHECK(p.components[1].free_curves == 4);
  CHECK(p.components[1].caps_added == 1);
  CHECK(p.caps_added == 1);
  CHECK(p.not_united.empty());
  CHECK(model.closed());
  // The cube less the square B covers on x = 1, plus B's four sides beyond
  // x = 1 (0.5 x 0.5 each) and its cap at x = 1.5.
  CHECK(total_area(model) == Approx(6.0 - 0.25 + 4 * 0.25 + 0.25).epsilon(1e-9));
  const auto [m, q] = mesh_checked(model, 0.05);
  for (const auto& [e, n] : edge_uses(m)) CHECK(n == 2);
}

TEST_CASE("a closed solid passes through the preparation unchanged") {
  const Model model = model_from_shape(BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape());
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 1);
  CHECK(p.components[0].closed);
  CHECK(p.components[0].role == "solid");
  CHECK_FALSE(p.fused);
  CHECK(p.fallback.empty());
  CHECK(model.num_faces() == 3);
  for (int f = 1; f <= 3; ++f) CHECK(model.source_face(f) == f);
}

TEST_CASE("a strip narrower than the width given becomes one curve shared by the faces either side") {
  // A tapered plate, 1 deep, chord 1 from a leading edge 0.1 thick to a blunt
  // trailing edge 1e-4 thick: the trailing edge is a strip 1 x 1e-4.
  const double te = 1e-4;
  const gp_Pnt a(0, 0.05, 0), b(1, te / 2, 0), c(1, -te / 2, 0), d(0, -0.05, 0);
  const TopoDS_Shape profile = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire()).Face();
  const TopoDS_Shape plate = BRepPrimAPI_MakePrism(profile, gp_Vec(0, 0, 1)).Shape();
  REQUIRE(count_free_curves(plate) == 0);
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> replaced;
  auto follow = [&](const TopoDS_Face& from, const TopoDS_Face& to) { replaced.emplace_back(from, to); };
  int collapsed = 0;
  // Wider strips than the width stay.
  CHECK(collapse_strips(plate, te / 2, follow, collapsed).IsSame(plate));
  CHECK(collapsed == 0);
  const TopoDS_Shape thin = collapse_strips(plate, 2 * te, follow, collapsed);
  CHECK(collapsed == 1);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(thin, TopAbs_FACE, faces);
  CHECK(faces.Extent() == 5);
  CHECK(count_free_curves(thin) == 0);
  CHECK(BRepCheck_Analyzer(thin).IsValid());
  // The two skins, the two end caps: the faces beside the strip, rebuilt.
  CHECK(replaced.size() == 4);
  // One closed surface meshes, its area the plate's less the strip's.
  const Model model = model_from_shape(thin);
  const SurfaceMesh m = mesh_closed(model, 0.05);
  double area = 0;
  for (const auto& t : m.tris) area += 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
  const double skin = std::hypot(1.0, 0.05 - te / 2), cap = 0.5 * (0.1 + te);
  CHECK(area == Approx(2 * skin + 2 * cap + 0.1).epsilon(1e-3));
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

namespace {

// A unit-wide strip in the plane y = 0..1 made of two cubic Bezier spans in
// u joined at a triple knot u = 1 (C0 in its parametrisation): the first span
// runs from x = 0 to 1 along +x; the second continues to `end` from there,
// reached with `speed` times the first span's parametric speed.
TopoDS_Shape two_span_strip(const gp_Vec& second, double speed) {
  TColgp_Array2OfPnt poles(1, 7, 1, 2);
  const gp_Vec first(1, 0, 0);
  for (int j = 1; j <= 2; ++j) {
    const gp_Vec y(0, j - 1, 0);
    for (int i = 0; i <= 3; ++i) poles(i + 1, j) = gp_Pnt(0, 0, 0).Translated(first * (i / 3.0) + y);
    for (int i = 1; i <= 3; ++i) poles(i + 4, j) = gp_Pnt(1, 0, 0).Translated(second * (speed * i / 3.0) + y);
  }
  TColStd_Array1OfReal uk(1, 3), vk(1, 2);
  TColStd_Array1OfInteger um(1, 3), vm(1, 2);
  uk(1) = 0, uk(2) = 1, uk(3) = 2;
  um(1) = 4, um(2) = 3, um(3) = 4;
  vk(1) = 0, vk(2) = 1;
  vm(1) = 2, vm(2) = 2;
  Handle(Geom_BSplineSurface) s = new Geom_BSplineSurface(poles, uk, vk, um, vm, 3, 1);
  return BRepBuilderAPI_MakeFace(s, 1e-7).Shape();
}

}  // namespace

TEST_CASE("faces split along knot lines where the surface folds or its parametrisation jumps", "[prepare]") {
  struct Case {
    const char* name;
    gp_Vec second;
    double speed;
    int faces;
  };
  const double c = std::cos(2 * kPi / 3), s = std::sin(2 * kPi / 3);
  for (const Case& k : {Case{"smooth: same direction, same speed", gp_Vec(1, 0, 0), 1.0, 1},
                        Case{"jump: same direction, five times the speed", gp_Vec(1, 0, 0), 5.0, 2},
                        Case{"crease: turned by 120 degrees", gp_Vec(c, 0, s), 1.0, 2},
                        Case{"mild turn: 10 degrees", gp_Vec(std::cos(0.17), 0, std::sin(0.17)), 1.0, 1}}) {
    SECTION(k.name) {
      const Model model = model_from_shape(two_span_strip(k.second, k.speed));
      REQUIRE(model.num_faces() == k.faces);
      CHECK(model.info().preparation.faces_split_at_folds == (k.faces > 1 ? 1 : 0));
      const double length = 1 + k.second.Magnitude() * k.speed;
      double area = 0;
      for (int f = 1; f <= model.num_faces(); ++f) {
        CHECK(model.source_face(f) == 1);
        area += model.face_area(f);
      }
      CHECK(area == Approx(length).epsilon(1e-6));
      // The knot line is a curve: the mesh has nodes on it, at x = 1 in the
      // first span's end plane, and no triangle crosses it.
      const UniformSize h(0.1);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      REQUIRE(m.failures.empty());
      CHECK(q.inverted == 0);
      CHECK(q.below_12 == 0);
      if (k.faces > 1) {
        int on_line = 0;
        for (size_t i = 0; i < m.xyz.size(); ++i)
          on_line += m.node_dim[i] <= 1 && std::abs(m.xyz[i].x() - 1) < 1e-9 && std::abs(m.xyz[i].z()) < 1e-9;
        CHECK(on_line >= 11);  // the line y = 0..1 at h = 0.1, ends included
      }
    }
  }
  // The manta's pods fold over at knots and its body patches change speed
  // across them: the preparation splits them, and the split pieces keep
  // their source face ids.
  const Model manta = load_model(test::model_path("manta2_openvsp.stp"));
  CHECK(manta.info().preparation.faces_split_at_folds > 0);
  for (int f = 1; f <= manta.num_faces(); ++f) CHECK(manta.source_face(f) >= 1);
}
