#include "io/sizing_report.h"

#include <array>
#include <iomanip>

namespace sizemesh {

void print_sizing_summary(const BackgroundMesh& bg, const SizeMap& m, const SmoothStats& s, std::ostream& out) {
  std::array<int, kNumLimits> count{};
  for (Limit l : m.limit) ++count[static_cast<int>(l)];
  out << "initial sizes (h_min " << m.h_min << ", h_max " << m.h_max << "), vertices limited by:\n";
  for (int i = 0; i < kNumLimits; ++i)
    if (count[i]) out << "  " << std::setw(24) << std::left << limit_name(static_cast<Limit>(i)) << count[i] << "\n";
  out << "smoothing: " << s.lowered << " of " << bg.num_vertices() << " vertices lowered, at most by a factor "
      << std::setprecision(4) << s.max_reduction << "; " << s.rounds << " edge/triangle rounds, "
      << s.triangle_corrections << " triangle corrections";
  if (s.degenerate_triangles) out << ", " << s.degenerate_triangles << " zero-area triangles skipped";
  if (s.steep_triangles) out << ", " << s.steep_triangles << " triangles left over their bound after " << s.rounds << " rounds";
  out << "\n"
      << "time: curvature " << m.t_curvature << " s, proximity " << m.t_proximity << " s, gaps " << m.t_gap
      << " s, user " << m.t_user << " s, edge stage " << s.t_edge << " s, triangle stage " << s.t_triangle << " s\n";
}

}  // namespace sizemesh
