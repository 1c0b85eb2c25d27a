// Curve discretisation at sharp corners (beyond the paper).
//
// Where two curves of a face's loop leave a B-rep point so close together
// that one element out the wedge between them is under kWedgeWidth = 0.25 of
// the element size h (an angle alpha under 14 deg, or curves leaving tangent
// to each other), the wedge stays narrower than the elements for a length of
// about h / alpha, and nodes at equal steps along both sides fill it with a
// strip of slivers. Instead the first node on both curves is placed where
// the wedge is kWedgeWidth h wide (r = kWedgeWidth h / tan alpha): the corner
// gets one triangle with the CAD's own angle and the strip beyond starts well
// shaped. A first segment is at most 6 h long, takes at most 0.4 of its curve
// and turns at most 20 deg; a curve shorter than 8 h keeps its equal steps. A corner under 60 deg with such a long first
// segment on one side gets it on the other side too (else that corner fills
// with slivers between a long and a short segment).
//
// Inputs:
//   g        the B-rep (loops, curve tangents)
//   loops    #faces+1 boundary loops of every face
//   samples  #curves+1 sampled curves (empty where a curve could not be sampled)
//   field    the size field: under its deviation bound (accuracy(); 0:
//            none) a first segment is at most the chord of that height on
//            the face at the corner (SizeField::deviation_chord; a long lead
//            on a curved face would be where the mesh lies farthest off the CAD)
// Output, per curve: the arc length of its first segment at t0 and at t1
// (0: the ordinary discretisation there).
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/curve_samples.h"

namespace sizemesh {

std::vector<std::array<double, 2>> corner_leads(const Geometry& g, const std::vector<std::vector<FaceLoop>>& loops,
                                                const std::vector<CurveSamples>& samples, const SizeField& field);

}  // namespace sizemesh
