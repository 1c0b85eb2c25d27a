// Pieces of a face divided at its folds: rebuilt for sewing, measured, healed.
#pragma once

#include <TopoDS_Face.hxx>

#include <vector>

namespace sizemesh::detail {

// `piece` rebuilt for the sewing of loose pieces: without the strips along
// its border that collapse onto a curve (OpenVSP's sharp trailing edges;
// the borders either side of such strips then run on one curve, for the
// sewing to join), and divided at the knots where a border runs back on
// itself (so each half of that border can sew to the other). `piece` alone
// when neither applies or it is not a B-spline face over a whole domain.
std::vector<TopoDS_Face> rebuild_piece(const TopoDS_Face& piece, double tol);

// True when `piece` has no area next to its face's `whole_area`.
bool empty(const TopoDS_Face& piece, double whole_area);

// True when a piece of f has no area: its surface collapses there.
bool empty_piece(const TopoDS_Face& f, const std::vector<TopoDS_Face>& pieces);

// A valid copy of `piece`, healed by ShapeFix_Shape when it is not valid
// (the division gives new edges a tolerance smaller than their vertices
// need); null when healing does not make it a valid face.
TopoDS_Face healed(const TopoDS_Face& piece);

}  // namespace sizemesh::detail
