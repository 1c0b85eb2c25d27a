// How many triangles a size map asks for, known before any meshing: the
// budget of the face mesher and the guard against absurd size maps.
//
// An equilateral triangle of side h covers sqrt(3)/4 h^2, so a face meshed to
// the map gets about (4/sqrt(3)) * integral over the face of dA / h^2
// triangles. The integral is taken exactly over the face's background
// triangles, where h is linear.
//
// Inputs:
//   bg          background mesh (triangles classified on faces)
//   h           #V size per background vertex (smoothed map)
//   limit       #V what set each vertex's initial size (may be empty)
//   num_faces   faces of the model
// Output: TriangleEstimate; per_face is indexed by face id (1-based, [0] unused).
#pragma once

#include <array>
#include <vector>

#include "background/background_mesh.h"
#include "sizing/size_map.h"

namespace sizemesh {

struct TriangleEstimate {
  std::vector<double> per_face;
  double total = 0;
  // Share of the total whose smallest corner size was set by each criterion
  // (index: Limit), to tell a user which option drives the count.
  std::array<double, kNumLimits> by_limit{};
  Limit dominant() const;
};

// Integral of 1/h^2 over a triangle of this area with h linear between its corner values.
double inverse_square_integral(double area, double h1, double h2, double h3);

TriangleEstimate estimate_triangles(const BackgroundMesh& bg, const std::vector<double>& h,
                                    const std::vector<Limit>& limit, int num_faces);

}  // namespace sizemesh
