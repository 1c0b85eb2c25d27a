// Faces classified against solids by points spread over them (Solids, cad/inside_solids.h); solids of shells.
#include "cad/inside_solids.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Precision.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <algorithm>

#include "cad/occt_model.h"

namespace sizemesh::detail {
namespace {

// Points inside the face (not on its boundary), found on a uv grid: the
// centre first, then outwards; at most `wanted`, spread over the grid.
std::vector<gp_Pnt> interior_points(const TopoDS_Face& f, int wanted) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d inside(f, Precision::PConfusion());
  BRepAdaptor_Surface s(f, false);
  constexpr int n = 9;
  std::vector<gp_Pnt> found;
  for (int k = 0; k < n * n; ++k) {
    const int i = (n / 2 + (k % n + 1) / 2 * ((k % n) % 2 ? 1 : -1)) % n;
    const int j = (n / 2 + (k / n + 1) / 2 * ((k / n) % 2 ? 1 : -1)) % n;
    const double u = u0 + (u1 - u0) * (i + 0.5) / n, v = v0 + (v1 - v0) * (j + 0.5) / n;
    if (inside.Perform(gp_Pnt2d(u, v)) == TopAbs_IN) found.push_back(s.Value(u, v));
  }
  if (static_cast<int>(found.size()) <= wanted) return found;
  std::vector<gp_Pnt> out;
  for (int k = 0; k < wanted; ++k) out.push_back(found[k * found.size() / wanted]);
  return out;
}

}  // namespace

Solids::Solids(const std::vector<TopoDS_Shape>& solids, double tol)
    : solids_(solids), classifiers_(solids.size()), tol_(tol) {
  for (const auto& s : solids_) {
    boxes_.emplace_back();
    BRepBndLib::Add(s, boxes_.back(), false);
    boxes_.back().Enlarge(tol);
  }
}

bool Solids::hold_whole(const TopoDS_Face& f, int n) const {
  const std::vector<gp_Pnt> points = interior_points(f, n);
  if (points.empty()) return false;
  for (size_t i = 0; i < solids_.size(); ++i) {
    if (std::any_of(points.begin(), points.end(), [&](const gp_Pnt& p) { return boxes_[i].IsOut(p); })) continue;
    if (std::all_of(points.begin(), points.end(), [&](const gp_Pnt& p) { return within(i, p); })) return true;
  }
  return false;
}

bool Solids::hold(const TopoDS_Face& f) const {
  const std::vector<gp_Pnt> points = interior_points(f, 5);
  for (size_t i = 0; i < solids_.size(); ++i) {
    const auto in_box =
        std::count_if(points.begin(), points.end(), [&](const gp_Pnt& p) { return !boxes_[i].IsOut(p); });
    if (2 * in_box <= static_cast<long>(points.size())) continue;
    const auto in = std::count_if(points.begin(), points.end(), [&](const gp_Pnt& p) { return within(i, p); });
    if (2 * in > static_cast<long>(points.size())) return true;
  }
  return false;
}

bool Solids::within(size_t i, const gp_Pnt& p) const {
  if (!classifiers_[i]) classifiers_[i] = std::make_unique<BRepClass3d_SolidClassifier>(solids_[i]);
  classifiers_[i]->Perform(p, tol_);
  const TopAbs_State st = classifiers_[i]->State();
  return st == TopAbs_IN || st == TopAbs_ON;
}

std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& sewn) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    const TopoDS_Solid solid = solid_from_shell(TopoDS::Shell(ex.Current()));
    if (solid.IsNull()) return {};
    out.push_back(solid);
  }
  return out;
}

}  // namespace sizemesh::detail
