// The union's time budget (union_budget, cad/model.h) and whether the union of meshes takes over.
#pragma once

#include <cstddef>

#include "cad/model.h"

namespace sizemesh::detail {

// Without a flow domain, the union of meshes takes over what the B-rep union
// leaves (mesher/mesh_union.h) in seconds, and closed: 1.5 s per component
// within 4 to 8 s, repair included, so the preparation ends within 10 s with
// its last splits. A fuse of OpenVSP's B-splines of hundreds of spans (every
// edge against every face it reaches) that would take 10 s to a minute is
// not waited for: the union of meshes does the same in 2 to 5 s. The fuses
// that end (the F-16's and the manta's, 2 and 2.6 s) end with room to
// spare. Inside a flow domain nothing takes over: 4 s per component, at
// least 12 s.
bool meshes_take_over(const LoadOptions& o);

// The budget for `components` components, unless options.union_seconds sets it.
double default_budget(const LoadOptions& o, size_t components);

}  // namespace sizemesh::detail
