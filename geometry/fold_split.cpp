// Faces split along knot lines where their surface folds over within the
// smallest element size or its parametrisation jumps (split_folds,
// geometry/occt_model.h).
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <GProp_GProps.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <BRep_Builder.hxx>
#include <BRepTools.hxx>
#include <TopoDS_Compound.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeExtend.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeUpgrade_FaceDivide.hxx>
#include <ShapeUpgrade_ShapeDivide.hxx>
#include <ShapeUpgrade_SplitSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HSequenceOfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <map>
#include <set>
#include <vector>
#include <cmath>
#include <limits>

#include "geometry/occt_model.h"

namespace sizemesh {
namespace {

constexpr int kSamples = 24;          // along each knot line
constexpr double kFoldCos = 0.5;      // normals more than 60 deg apart across the band
constexpr double kJump = 3.0;        // parametric speed ratio across a knot line
constexpr double kStripBands = 20;   // narrowest strip a jump split may leave, in fold bands (10 default h_min)
constexpr int kRounds = 3;            // divisions tried, each without the faces the last one broke

// The point of s on the iso-line `along_u ? u = t : v = t` at w of the other parameter.
gp_Pnt iso_point(const Geom_Surface& s, bool along_u, double t, double w) {
  return along_u ? s.Value(t, w) : s.Value(w, t);
}

// Unit normal of s at (u, v); false where it is undefined.
bool normal_at(const Geom_Surface& s, double u, double v, gp_Dir& n) {
  gp_Pnt p;
  gp_Vec du, dv;
  s.D1(u, v, p, du, dv);
  const gp_Vec c = du.Crossed(dv);
  if (!(c.Magnitude() > 1e-300)) return false;
  n = gp_Dir(c);
  return true;
}

// How strongly, somewhere in [lo, hi] of the other parameter, the knot line
// `along_u ? u = t : v = t` is a fold or a jump:
//  - fold: the surface turns over within `band` (model units) on either side
//    (a sharp or nearly sharp trailing edge, a crease), narrower than any
//    element can follow;
//  - jump: the parametric speed across the line changes by more than kJump
//    from one side to the other, along most of the line. A front in uv sizes its triangles by the
//    metric where it stands; across such a line the same uv step is several
//    times longer in space, and triangles straddling it fold over.
// With `crease_only`, only a fold along most of the line counts (a cap
// built into a skin, whose crease runs from end to end), never a jump or a
// fold at a few points of it (a leading edge sharpening towards a tip).
double splits_at(const Geom_BSplineSurface& s, bool along_u, double t, double lo, double hi, double t_lo,
                 double t_hi, double band, bool crease_only) {
  std::vector<double> ratios;
  double fold = 0;
  int folded = 0, defined = 0;
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
    double side[2], speed[2];
    for (int k = 0; k < 2; ++k) {  // parameter step that covers `band` in space on each side
      const double sign = k == 0 ? -1 : 1;
      const double e = 1e-6 * (t_hi - t_lo);
      gp_Pnt p;
      gp_Vec du, dv;
      if (along_u) s.D1(t + sign * e, w, p, du, dv);
      else s.D1(w, t + sign * e, p, du, dv);
      speed[k] = (along_u ? du : dv).Magnitude();
      double step = speed[k] > 0 ? band / speed[k] : (t_hi - t_lo);
      step = std::min(step, k == 0 ? t - t_lo : t_hi - t);
      side[k] = t + sign * step;
    }
    const double slow = std::min(speed[0], speed[1]), fast = std::max(speed[0], speed[1]);
    if (slow > 0) ratios.push_back(fast / slow);
    gp_Dir n0, n1;
    const bool ok = along_u ? normal_at(s, side[0], w, n0) && normal_at(s, side[1], w, n1)
                            : normal_at(s, w, side[0], n0) && normal_at(s, w, side[1], n1);
    defined += ok;
    if (ok && n0.Dot(n1) < kFoldCos) fold = std::max(fold, 1 - n0.Dot(n1)), ++folded;
  }
  // Most of the line, counted where the surface has a normal on both sides
  // (a section whose trailing-edge spans collapse to a point has none there),
  // and that over a third of the line at least.
  if (crease_only) return 3 * defined > kSamples + 1 && 2 * folded > defined ? 2 + fold : 0;
  if (fold > 0) return 2 + fold;
  // A jump along most of the line (the median: a pole at one end of it has
  // any ratio at all).
  if (ratios.empty()) return 0;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2] > kJump ? 1 : 0;
}

// Median distance in space between the iso-lines t_a and t_b (u = t when
// along_u), over the other parameter's range [lo, hi]: the width of the strip
// a split between them would leave.
double strip_width(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi) {
  std::vector<double> d;
  for (int j = 0; j <= kSamples / 3; ++j) {
    const double w = lo + (hi - lo) * (j + 0.5) / (kSamples / 3 + 1);
    d.push_back(iso_point(s, along_u, t_a, w).Distance(iso_point(s, along_u, t_b, w)));
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// True when the strip between the iso-lines t_a and t_b (u = t when
// along_u), over the other parameter's range [lo, hi], lies on one plane
// within `band` and is wider than `band` somewhere: a cap built into the
// skin, such as OpenVSP's root and tip caps folded onto the chord. A strip
// of no width (a section of zero thickness folded onto its chord, as a wing
// root lying on a fuselage's crest) is no cap: splitting it off would leave
// the skin's edge a line run twice.
bool flat_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                double band) {
  double widest = 0;
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
    widest = std::max(widest, iso_point(s, along_u, t_a, w).Distance(iso_point(s, along_u, t_b, w)));
  }
  if (!(widest > band)) return false;
  std::vector<gp_Pnt> points;
  gp_XYZ normal(0, 0, 0);
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= kSamples; ++j) {
      const double t = t_a + (t_b - t_a) * (i + 0.5) / 5, w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
      const double u = along_u ? t : w, v = along_u ? w : t;
      points.push_back(s.Value(u, v));
      gp_Dir n;
      if (!normal_at(s, u, v, n)) continue;
      normal += n.XYZ() * (normal.Dot(n.XYZ()) < 0 ? -1.0 : 1.0);
    }
  if (!(normal.Modulus() > 0)) return false;
  normal.Normalize();
  gp_XYZ centre(0, 0, 0);
  for (const auto& p : points) centre += p.XYZ();
  centre /= static_cast<double>(points.size());
  for (const auto& p : points)
    if (std::abs((p.XYZ() - centre).Dot(normal)) > band) return false;
  return true;
}

// True when the strip between the iso-lines t_a and t_b (u = t when
// along_u) collapses onto a curve: across it the surface does not move by
// more than `tol` anywhere over [lo, hi]. OpenVSP writes a sharp trailing
// edge as such spans; a face's piece there has no area and no normal.
bool collapsed_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                     double tol) {
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * j / kSamples;
    const gp_Pnt a = iso_point(s, along_u, t_a, w);
    for (int i = 1; i <= 4; ++i) {
      const double t = t_a + (t_b - t_a) * i / 4;
      if (iso_point(s, along_u, t, w).Distance(a) > tol) return false;
    }
  }
  return true;
}

// Largest distance of a sample of `a` from the polyline `b`.
double distance_to(const std::vector<gp_Pnt>& a, const std::vector<gp_Pnt>& b) {
  double farthest = 0;
  for (const gp_Pnt& p : a) {
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < b.size(); ++i) {
      const gp_Vec e(b[i], b[i + 1]), w(b[i], p);
      const double ee = e.SquareMagnitude(), t = ee > 0 ? std::clamp(w.Dot(e) / ee, 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, w.Subtracted(e.Multiplied(t)).Magnitude());
    }
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

// How far the iso-line `along_u ? u = c : v = c` is from running back on
// itself at the knot t of the other parameter: the distance between its
// parts over [t0, t] and [t, t1] (both ways), which start and end at one
// point. A section collapsed onto its chord, as at the end of OpenVSP's tip
// cap, goes from the trailing edge to the leading edge and back: 0 at the
// leading edge's knot. Infinite when a part is shorter than 10 `tol`.
double fold_back_gap(const Geom_BSplineSurface& s, bool along_u, double c, double t0, double t, double t1,
                     double tol) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  auto at = [&](double w) { return iso_point(s, along_u, c, w); };
  if (at(t0).Distance(at(t1)) > tol) return kInf;
  // The line turns back at t: its steps just before and just after point
  // opposite ways (the samples below are only taken where it does).
  const double e = 1e-3 * std::min(t - t0, t1 - t);
  const gp_Vec before(at(t - e), at(t)), after(at(t), at(t + e));
  if (!(before.Magnitude() > 0 && after.Magnitude() > 0) || before.Dot(after) > -0.9 * before.Magnitude() * after.Magnitude())
    return kInf;
  constexpr int n = 8 * kSamples;
  std::vector<gp_Pnt> part[2];
  double length[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const double a = k == 0 ? t0 : t, b = k == 0 ? t : t1;
    for (int i = 0; i <= n; ++i) {
      const double w = a + (b - a) * i / n;
      part[k].push_back(at(w));
      if (i > 0) length[k] += part[k][i].Distance(part[k][i - 1]);
    }
  }
  if (!(std::min(length[0], length[1]) > 10 * tol)) return kInf;
  return std::max({part[0].front().Distance(part[1].back()), distance_to(part[0], part[1]),
                   distance_to(part[1], part[0])});
}

// `piece` rebuilt for the sewing of loose pieces: without the strips along
// its border that collapse onto a curve (OpenVSP's sharp trailing edges;
// the borders either side of such strips then run on one curve, for the
// sewing to join), and divided at the knots where a border runs back on
// itself (so each half of that border can sew to the other). `piece` alone
// when neither applies or it is not a B-spline face over a whole domain.
std::vector<TopoDS_Face> rebuild_piece(const TopoDS_Face& piece, double tol) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(piece);
  if (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface)) surface = trimmed->BasisSurface();
  const Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (b.IsNull()) return {piece};
  double u0, u1, v0, v1;
  BRepTools::UVBounds(piece, u0, u1, v0, v1);
  // Bounded by its domain's borders alone: every edge runs along one.
  const double eu = 1e-7 * (u1 - u0), ev = 1e-7 * (v1 - v0);
  for (TopExp_Explorer ex(piece, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), piece, f, l);
    if (c.IsNull()) return {piece};
    bool on[4] = {true, true, true, true};
    for (double t : {f, 0.5 * (f + l), l}) {
      const gp_Pnt2d p = c->Value(t);
      on[0] = on[0] && std::abs(p.X() - u0) <= eu, on[1] = on[1] && std::abs(p.X() - u1) <= eu;
      on[2] = on[2] && std::abs(p.Y() - v0) <= ev, on[3] = on[3] && std::abs(p.Y() - v1) <= ev;
    }
    if (!(on[0] || on[1] || on[2] || on[3])) return {piece};
  }
  double range[2][2] = {{u0, u1}, {v0, v1}};
  bool changed = false;
  for (int d = 0; d < 2; ++d) {
    const bool along_u = d == 0;
    const double t0 = range[d][0], t1 = range[d][1], lo = along_u ? v0 : u0, hi = along_u ? v1 : u1;
    const double eps = 1e-9 * (t1 - t0);
    const int knots = along_u ? b->NbUKnots() : b->NbVKnots();
    for (int k = 1; k <= knots; ++k) {
      const double t = along_u ? b->UKnot(k) : b->VKnot(k);
      if (t <= t0 + eps || t >= t1 - eps) continue;
      if (t > range[d][0] && collapsed_strip(*b, along_u, t0, t, lo, hi, tol)) range[d][0] = t, changed = true;
      if (t < range[d][1] && collapsed_strip(*b, along_u, t, t1, lo, hi, tol))
        range[d][1] = std::min(range[d][1], t), changed = true;
    }
  }
  if (!(range[0][0] < range[0][1]) || !(range[1][0] < range[1][1])) return {piece};
  // A cut in u where a border v = const folds back, and in v where a border u = const does.
  std::vector<double> cuts[2] = {{range[0][0]}, {range[1][0]}};
  for (int d = 0; d < 2; ++d) {
    const bool along_u = d == 0;  // the cut's parameter is u; the borders are v = const
    const double t0 = range[d][0], t1 = range[d][1], eps = 1e-9 * (t1 - t0);
    const int knots = along_u ? b->NbUKnots() : b->NbVKnots();
    double best_gap = std::numeric_limits<double>::infinity(), best = t0;
    for (int k = 1; k <= knots; ++k) {
      const double t = along_u ? b->UKnot(k) : b->VKnot(k);
      if (t <= t0 + eps || t >= t1 - eps) continue;
      for (double c : {range[1 - d][0], range[1 - d][1]}) {
        const double gap = fold_back_gap(*b, !along_u, c, t0, t, t1, tol);
        if (gap <= tol && gap < best_gap) best_gap = gap, best = t;
      }
    }
    if (best_gap <= tol) cuts[d].push_back(best), changed = true;
    cuts[d].push_back(t1);
  }
  if (!changed) return {piece};
  std::vector<TopoDS_Face> out;
  for (size_t i = 0; i + 1 < cuts[0].size(); ++i)
    for (size_t j = 0; j + 1 < cuts[1].size(); ++j) {
      // A segment of its own, as the division's pieces have: the face's box
      // is its poles'.
      Handle(Geom_BSplineSurface) segment = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
      segment->Segment(cuts[0][i], cuts[0][i + 1], cuts[1][j], cuts[1][j + 1]);
      BRepBuilderAPI_MakeFace make(segment, Precision::Confusion());
      if (!make.IsDone() || !BRepCheck_Analyzer(make.Face()).IsValid()) return {piece};
      TopoDS_Face f = make.Face();
      f.Orientation(piece.Orientation());
      out.push_back(f);
    }
  return out;
}

// Knot values that split [t0, t1] (with their strength: 1 a jump, 2 and
// more a fold, the sharper the more). A strip narrower than `min_width`
// meshes into triangles thinner than the elements: of the two lines that
// bound it, the weaker goes (a jump before a fold; of folds close together,
// as on a leading edge of small radius where every knot turns the normal,
// the sharpest stays). A fold next to the face's border stays.
std::vector<double> kept_splits(const Geom_BSplineSurface& s, bool along_u, std::vector<std::pair<double, double>> cand,
                                double t0, double t1, double lo, double hi, double min_width) {
  for (bool dropped = true; dropped && !cand.empty();) {
    dropped = false;
    double narrowest = min_width;
    size_t drop = cand.size();
    for (size_t i = 0; i <= cand.size(); ++i) {  // strip i lies between line i-1 and line i
      const double a = i == 0 ? t0 : cand[i - 1].first, b = i == cand.size() ? t1 : cand[i].first;
      const double lower = i == 0 ? cand[0].second : i == cand.size() ? cand[i - 1].second
                                                                       : std::min(cand[i - 1].second, cand[i].second);
      const size_t weaker = i == 0 ? 0 : i == cand.size() ? i - 1 : (cand[i - 1].second <= cand[i].second ? i - 1 : i);
      if ((i == 0 || i == cand.size()) && lower >= 2) continue;  // a fold by the border
      const double w = strip_width(s, along_u, a, b, lo, hi);
      if (w < narrowest) narrowest = w, drop = weaker;
    }
    if (drop < cand.size()) cand.erase(cand.begin() + drop), dropped = true;
  }
  std::vector<double> out;
  for (const auto& c : cand) out.push_back(c.first);
  return out;
}

// Which knot lines a division splits at.
enum class Lines { Both, U, V };

// Lines (along u, at t) of a surface that a division must not split at.
using Banned = std::map<const Geom_Surface*, std::set<std::pair<bool, double>>>;

size_t count_banned(const Banned& banned) {
  size_t n = 0;
  for (const auto& [surface, lines] : banned) n += lines.size();
  return n;
}

// Split values of one face's surface: its C0 knots (multiplicity at least the
// degree) where the surface folds or its parametric speed jumps.
class FoldSplitter : public ShapeUpgrade_SplitSurface {
 public:
  FoldSplitter(double band, Lines lines, const std::set<const Geom_Surface*>& whole, const Banned& banned,
               const std::set<const Geom_Surface*>* only, bool crease_only)
      : band_(band), lines_(lines), whole_(whole), banned_(banned), only_(only), crease_only_(crease_only) {}

  void Compute(const Standard_Boolean /*segment*/) override {
    if (whole_.count(mySurface.get()) || (only_ && !only_->count(mySurface.get()))) return;
    Handle(Geom_Surface) base = mySurface;
    if (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(base)) base = trimmed->BasisSurface();
    const Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(base);
    if (b.IsNull()) return;
    const double u0 = myUSplitValues->Value(1), u1 = myUSplitValues->Value(myUSplitValues->Length());
    const double v0 = myVSplitValues->Value(1), v1 = myVSplitValues->Value(myVSplitValues->Length());
    const double eps_u = 1e-9 * std::max(u1 - u0, 1e-300), eps_v = 1e-9 * std::max(v1 - v0, 1e-300);
    // Knot lines of full multiplicity inside the face that qualify: a fold
    // or jump (splits_at), and with crease_only one that bounds a flat cap.
    auto candidates = [&](bool along_u) {
      std::vector<std::pair<double, double>> cand;
      const double t0 = along_u ? u0 : v0, t1 = along_u ? u1 : v1, lo = along_u ? v0 : u0, hi = along_u ? v1 : u1;
      const double eps = along_u ? eps_u : eps_v;
      const int knots = along_u ? b->NbUKnots() : b->NbVKnots(), degree = along_u ? b->UDegree() : b->VDegree();
      for (int k = 2; k < knots && lines_ != (along_u ? Lines::V : Lines::U); ++k) {
        const double t = along_u ? b->UKnot(k) : b->VKnot(k);
        const int multiplicity = along_u ? b->UMultiplicity(k) : b->VMultiplicity(k);
        if (multiplicity < degree || t <= t0 + eps || t >= t1 - eps || is_banned(along_u, t, eps)) continue;
        if (const double why = splits_at(*b, along_u, t, lo, hi, t0, t1, band_, crease_only_);
            why > 0 && (!crease_only_ || flat_strip(*b, along_u, t0, t, lo, hi, band_) ||
                        flat_strip(*b, along_u, t, t1, lo, hi, band_)))
          cand.push_back({t, why});
      }
      return cand;
    };
    const std::vector<std::pair<double, double>> cand_u = candidates(true), cand_v = candidates(false);
    for (double t : kept_splits(*b, true, cand_u, u0, u1, v0, v1, kStripBands * band_)) insert(myUSplitValues, t);
    for (double t : kept_splits(*b, false, cand_v, v0, v1, u0, u1, kStripBands * band_)) insert(myVSplitValues, t);
    if (myUSplitValues->Length() > 2 || myVSplitValues->Length() > 2)
      myStatus |= ShapeExtend::EncodeStatus(ShapeExtend_DONE1);
  }

 private:
  bool is_banned(bool along_u, double t, double eps) const {
    const auto it = banned_.find(mySurface.get());
    if (it == banned_.end()) return false;
    return std::any_of(it->second.begin(), it->second.end(),
                       [&](const auto& line) { return line.first == along_u && std::abs(line.second - t) <= eps; });
  }
  static void insert(const Handle(TColStd_HSequenceOfReal)& values, double t) {
    int i = 1;
    while (i <= values->Length() && values->Value(i) < t) ++i;
    values->InsertBefore(i, t);
  }
  double band_;
  Lines lines_;
  const std::set<const Geom_Surface*>& whole_;  // surfaces not to divide
  const Banned& banned_;                        // lines not to divide at
  const std::set<const Geom_Surface*>* only_;   // when given, the only surfaces to divide
  bool crease_only_;  // only folds along most of a line (splits_at) that bound a flat cap
};

double area_of(const TopoDS_Face& f) {
  GProp_GProps g;
  BRepGProp::SurfaceProperties(f, g);
  return std::abs(g.Mass());
}

// True when `piece` has no area next to its face's `whole_area`.
bool empty(const TopoDS_Face& piece, double whole_area) { return area_of(piece) <= 1e-9 * whole_area; }

// True when a piece of f has no area: its surface collapses there.
bool empty_piece(const TopoDS_Face& f, const std::vector<TopoDS_Face>& pieces) {
  const double whole = area_of(f);
  return std::any_of(pieces.begin(), pieces.end(), [&](const TopoDS_Face& piece) { return empty(piece, whole); });
}

// A valid copy of `piece`, healed by ShapeFix_Shape when it is not valid
// (the division gives new edges a tolerance smaller than their vertices
// need); null when healing does not make it a valid face.
TopoDS_Face healed(const TopoDS_Face& piece) {
  if (BRepCheck_Analyzer(piece).IsValid()) return piece;
  ShapeFix_Shape fix(piece);
  fix.Perform();
  const TopoDS_Shape out = fix.Shape();
  if (out.IsNull() || out.ShapeType() != TopAbs_FACE || !BRepCheck_Analyzer(out).IsValid()) return {};
  return TopoDS::Face(out);
}

// One division of the faces of `shape` (those on `only`'s surfaces, when
// given) at the knot lines `lines`. `split` is increased by the faces divided;
// `collapsed` gets the surfaces left whole because a piece had no area,
// `pieces_made` the surfaces of the pieces. With `loose`, the faces need not
// stay joined: each piece is healed on its own, and the result is a compound
// of faces for the caller to sew.
TopoDS_Shape divide(const TopoDS_Shape& shape, double band, Lines lines, const std::set<const Geom_Surface*>* only,
                    const std::function<void(const TopoDS_Face&, const TopoDS_Face&)>& follow, int& split,
                    std::set<const Geom_Surface*>& collapsed, std::set<const Geom_Surface*>& pieces_made, bool loose) {
  // Faces whose pieces come out invalid keep their surface whole (with
  // `loose`, lose the lines that bound the bad pieces); the rest are divided
  // again (a few rounds at most).
  std::set<const Geom_Surface*> whole;
  Banned banned;
  for (int round = 0; round < kRounds; ++round) {
    const size_t whole_before = whole.size(), banned_before = count_banned(banned);
    try {
      Handle(ShapeUpgrade_FaceDivide) faces = new ShapeUpgrade_FaceDivide;
      faces->SetSplitSurfaceTool(new FoldSplitter(band, lines, whole, banned, only, loose));
      ShapeUpgrade_ShapeDivide division(shape);
      division.SetSplitFaceTool(faces);
      division.SetSurfaceSegmentMode(true);
      if (!division.Perform() || !division.Status(ShapeExtend_DONE)) return shape;
      const TopoDS_Shape result = division.Result();
      if (result.IsNull()) return shape;
      // The divided edges keep their old flags: recompute them (and the
      // tolerances they need) before judging the result, over the whole
      // shape (edges the division left may not be same-parameter either).
      BRepLib::SameParameter(result, Precision::Confusion(), true);
      // Each face the division replaced, with its pieces (one piece: only its
      // edges were divided, by a neighbour's split; with `loose`, rebuilt and
      // healed each on its own), then one check of them all, on both cores.
      const Handle(ShapeBuild_ReShape) context = division.GetContext();
      struct Change {
        TopoDS_Face face;
        std::vector<TopoDS_Face> raw, pieces;
      };
      std::vector<Change> changes;
      TopoDS_Compound all_pieces;
      BRep_Builder cb;
      cb.MakeCompound(all_pieces);
      for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
        const TopoDS_Face& f = TopoDS::Face(ex.Current());
        const TopoDS_Shape now = context->Apply(f);
        if (now.IsSame(f)) continue;
        // Loose pieces of no area (a strip collapsed onto a curve) carry no
        // mesh: they go, and the sewing joins the pieces around them.
        Change c{f, {}, {}};
        const double whole_area = loose ? area_of(f) : 0;
        for (TopExp_Explorer p(now, TopAbs_FACE); p.More(); p.Next())
          if (!loose || !empty(TopoDS::Face(p.Current()), whole_area)) c.raw.push_back(TopoDS::Face(p.Current()));
        if (c.raw.empty()) continue;
        if (loose) {
          std::vector<TopoDS_Face> rebuilt;
          for (const TopoDS_Face& piece : c.raw)
            for (const TopoDS_Face& part : rebuild_piece(piece, 1e-3 * band)) rebuilt.push_back(part);
          c.raw = std::move(rebuilt);
        }
        for (const TopoDS_Face& piece : c.raw) {
          c.pieces.push_back(loose ? healed(piece) : piece);
          if (!c.pieces.back().IsNull()) cb.Add(all_pieces, c.pieces.back());
        }
        changes.push_back(std::move(c));
      }
      // Topology first (cheap), then the geometry (curves on their surfaces)
      // of the pieces that pass it: on a piece of no area, where the surface
      // collapses, the second alone takes most of a second, and the first
      // fails it anyway.
      const BRepCheck_Analyzer topology(all_pieces, false, true);
      TopoDS_Compound sound;
      cb.MakeCompound(sound);
      for (TopExp_Explorer p(all_pieces, TopAbs_FACE); p.More(); p.Next())
        if (topology.IsValid(p.Current())) cb.Add(sound, p.Current());
      const BRepCheck_Analyzer check(sound, true, true);
      auto good = [&](const TopoDS_Face& piece) {
        return !piece.IsNull() && topology.IsValid(piece) && check.IsValid(piece);
      };
      std::vector<std::pair<TopoDS_Face, std::vector<TopoDS_Face>>> replaced;
      bool valid = true;
      for (Change& c : changes) {
        const TopoDS_Face& f = c.face;
        if (!std::all_of(c.pieces.begin(), c.pieces.end(), good)) {
          const Geom_Surface* surface = BRep_Tool::Surface(f).get();
          if (loose) {
            // The lines that bound a bad piece are not tried again; the
            // face's other lines are.
            double u0, u1, v0, v1;
            BRepTools::UVBounds(f, u0, u1, v0, v1);
            const double eu = 1e-9 * (u1 - u0), ev = 1e-9 * (v1 - v0);
            for (size_t i = 0; i < c.raw.size(); ++i) {
              if (good(c.pieces[i])) continue;
              double a0, a1, b0, b1;
              BRepTools::UVBounds(c.raw[i], a0, a1, b0, b1);
              for (double t : {a0, a1})
                if (t > u0 + eu && t < u1 - eu) banned[surface].insert({true, t});
              for (double t : {b0, b1})
                if (t > v0 + ev && t < v1 - ev) banned[surface].insert({false, t});
            }
          } else {
            whole.insert(surface);
            if (empty_piece(f, c.pieces)) collapsed.insert(surface);
          }
          valid = false;
        }
        replaced.push_back({f, std::move(c.pieces)});
      }
      // The next round divides the same faces again unless this one left
      // more of them whole (or banned more lines): it would fail alike.
      if (!valid) {
        if (whole.size() == whole_before && count_banned(banned) == banned_before) return shape;
        continue;
      }
      // A closed shape stays closed (an open one gains free curves where its
      // free boundary is divided).
      if (!loose && !step_keeps_shape_valid(shape, result)) return shape;
      BRep_Builder b;
      TopoDS_Compound loose_faces;
      b.MakeCompound(loose_faces);
      for (TopExp_Explorer ex(shape, TopAbs_FACE); loose && ex.More(); ex.Next())
        if (context->Apply(ex.Current()).IsSame(ex.Current())) b.Add(loose_faces, ex.Current());
      for (const auto& [f, pieces] : replaced) {
        for (const TopoDS_Face& piece : pieces) {
          follow(f, piece), pieces_made.insert(BRep_Tool::Surface(piece).get());
          if (loose) b.Add(loose_faces, piece);
        }
        split += pieces.size() > 1;
      }
      return loose ? TopoDS_Shape(loose_faces) : result;
    } catch (const Standard_Failure&) {
      return shape;
    }
  }
  return shape;
}

}  // namespace

TopoDS_Shape split_folds(const TopoDS_Shape& shape, double band,
                         const std::function<void(const TopoDS_Face&, const TopoDS_Face&)>& follow, int& split,
                         bool loose) {
  split = 0;
  if (shape.IsNull() || !(band > 0)) return shape;
  std::set<const Geom_Surface*> collapsed, unused, u_pieces;
  TopoDS_Shape result = divide(shape, band, Lines::Both, nullptr, follow, split, collapsed, unused, loose);
  if (collapsed.empty()) return result;
  // A face whose division both ways leaves a piece of no area (a wing's
  // skin whose root cap collapses onto its chord, and its blunt trailing
  // edge onto a point there) is divided one way, at its u lines, then each
  // piece at its v lines: the caps come apart from the skin, and the skin
  // from its trailing edge.
  result = divide(result, band, Lines::U, &collapsed, follow, split, unused, u_pieces, loose);
  u_pieces.insert(collapsed.begin(), collapsed.end());
  return divide(result, band, Lines::V, &u_pieces, follow, split, unused, unused, loose);
}

}  // namespace sizemesh
