// Faces split along knot lines where their surface folds or its parametrisation jumps (split_folds).
//
// A fold counts where the surface turns over within the smallest element size
// (split_folds, cad/occt_model.h). The tests along a knot line are
// cad/knot_lines.cpp; what becomes of the pieces, cad/fold_pieces.cpp.
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Precision.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeExtend.hxx>
#include <ShapeUpgrade_FaceDivide.hxx>
#include <ShapeUpgrade_ShapeDivide.hxx>
#include <ShapeUpgrade_SplitSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HSequenceOfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "cad/fold_pieces.h"
#include "cad/knot_lines.h"
#include "cad/occt_model.h"

namespace sizemesh {
using namespace detail;  // the knot-line tests and the pieces' treatment
namespace {

constexpr double kStripBands = 20;   // narrowest strip a jump split may leave, in fold bands (10 default h_min)
constexpr int kRounds = 3;            // divisions tried, each without the faces the last one broke

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
    for (double t : kept_splits(*b, true, cand_u, u0, u1, v0, v1, kStripBands * band_, band_)) insert(myUSplitValues, t);
    for (double t : kept_splits(*b, false, cand_v, v0, v1, u0, u1, kStripBands * band_, band_)) insert(myVSplitValues, t);
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
        const double whole_area = loose ? face_area_exact(f) : 0;
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
        // Divided both ways at once, a face whose caps and trailing-edge
        // base meet at a corner where the surface collapses (OpenVSP's blunt
        // trailing edge at its root cap) leaves a piece of no area there: a
        // valid face the mesher cannot fill. It goes the way of an invalid one.
        const bool no_area = !loose && c.pieces.size() > 1 && empty_piece(f, c.pieces);
        if (no_area || !std::all_of(c.pieces.begin(), c.pieces.end(), good)) {
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
