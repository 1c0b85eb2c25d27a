// The union's time budget: per component, within bounds, longer inside a flow domain (cad/union_budget.h).
#include "cad/union_budget.h"

#include <algorithm>

#include "cad/components.h"
#include "cad/occt_model.h"

namespace sizemesh {
namespace detail {

bool meshes_take_over(const LoadOptions& o) { return !o.domain.active(); }

double default_budget(const LoadOptions& o, size_t components) {
  if (o.union_seconds > 0) return o.union_seconds;
  const double n = static_cast<double>(components);
  return meshes_take_over(o) ? std::clamp(1.5 * n, 4.0, 8.0) : std::max(12.0, 4.0 * n);
}

}  // namespace detail

using detail::components_of;
using detail::default_budget;

double union_budget(const CadFile& cad, const LoadOptions& options) {
  return default_budget(options, components_of(cad.impl().shape).size());
}

}  // namespace sizemesh
