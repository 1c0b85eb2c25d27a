// Tests on a B-spline surface's knot lines: folds, jumps, flat caps, collapsed strips, lines run back on themselves.
#pragma once

#include <Geom_BSplineSurface.hxx>

#include <utility>
#include <vector>

namespace sizemesh::detail {

// The distinct knots of s along u (along_u) or v inside (t0, t1), each more
// than 1e-9 of that range from its ends.
std::vector<double> knots_inside(const Geom_BSplineSurface& s, bool along_u, double t0, double t1);

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
                 double t_hi, double band, bool crease_only);

// True when the strip between the iso-lines t_a and t_b (u = t when
// along_u), over the other parameter's range [lo, hi], lies on one plane
// within `band` and is wider than `band` somewhere: a cap built into the
// skin, such as OpenVSP's root and tip caps folded onto the chord. A strip
// of no width (a section of zero thickness folded onto its chord, as a wing
// root lying on a fuselage's crest) is no cap: splitting it off would leave
// the skin's edge a line run twice.
bool flat_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                double band);

// True when the strip between the iso-lines t_a and t_b (u = t when
// along_u) collapses onto a curve: across it the surface does not move by
// more than `tol` anywhere over [lo, hi]. OpenVSP writes a sharp trailing
// edge as such spans; a face's piece there has no area and no normal.
bool collapsed_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                     double tol);

// How far the iso-line `along_u ? u = c : v = c` is from running back on
// itself at the knot t of the other parameter: the distance between its
// parts over [t0, t] and [t, t1] (both ways), which start and end at one
// point. A section collapsed onto its chord, as at the end of OpenVSP's tip
// cap, goes from the trailing edge to the leading edge and back: 0 at the
// leading edge's knot. Infinite when a part is shorter than 10 `tol`.
double fold_back_gap(const Geom_BSplineSurface& s, bool along_u, double c, double t0, double t, double t1,
                     double tol);

// Knot values that split [t0, t1] (with their strength: 1 a jump, 2 and
// more a fold, the sharper the more). A strip narrower than `min_width`
// meshes into triangles thinner than the elements: of the two lines that
// bound it, the weaker goes (a jump before a fold; of folds close together,
// as on a leading edge of small radius where every knot turns the normal,
// the sharpest stays). A fold next to the face's border stays, unless the
// strip it leaves there pinches to under `border_width` inside (a blunt
// trailing edge whose base thickness passes through zero along the span,
// measured over the surface).
std::vector<double> kept_splits(const Geom_BSplineSurface& s, bool along_u, std::vector<std::pair<double, double>> cand,
                                double t0, double t1, double lo, double hi, double min_width, double border_width);

}  // namespace sizemesh::detail
