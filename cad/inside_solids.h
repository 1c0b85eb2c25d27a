// Which faces lie inside closed solids (Solids), and the solids a sewn shape's shells bound.
#pragma once

#include <BRepClass3d_SolidClassifier.hxx>
#include <Bnd_Box.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include <memory>
#include <vector>

namespace sizemesh::detail {

// Solids asked whether a face lies inside one of them or on its boundary:
// most of a few points spread over it do, for one solid. One point alone may
// sit where another body touches the face (a jury strut's foot on a strut), or
// be misjudged by the classifier that close to the boundary (a planform plane
// in a thin wing). Solids whose box holds no more than half the points are
// not asked: the classifier can take seconds a point on a solid with crossing
// faces.
class Solids {
 public:
  Solids(const std::vector<TopoDS_Shape>& solids, double tol);
  // Every one of `n` points spread over f inside one solid or on its
  // boundary: a face wholly inside, not one that reaches out of it.
  bool hold_whole(const TopoDS_Face& f, int n) const;
  // Most of 5 points spread over f inside one solid or on its boundary.
  bool hold(const TopoDS_Face& f) const;

 private:
  // p inside solid i or on its boundary. The classifier is loaded once per
  // solid (loading maps its faces and boxes, most of a classification's cost).
  bool within(size_t i, const gp_Pnt& p) const;
  std::vector<TopoDS_Shape> solids_;
  mutable std::vector<std::unique_ptr<BRepClass3d_SolidClassifier>> classifiers_;
  std::vector<Bnd_Box> boxes_;
  double tol_;
};

// The solids bounded by the shells of a sewn shape (a wing whose halves
// close each on its own sews into two shells), or none when one of them
// bounds no solid.
std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& sewn);

}  // namespace sizemesh::detail
