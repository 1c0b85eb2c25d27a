// Why the size is what it is at a point of the mesh: the rule (Limit,
// sizing/size_map.h) that set the initial size of the nearest corner, in
// space, of the background triangle the size query walks to there. Written
// on the mesh's nodes as point data `limited_by`, as the background has it.
#pragma once

#include "background/background_mesh.h"
#include "sizing/size_map.h"
#include "sizing/size_query.h"

namespace sizemesh {

// -1 where the query finds no triangle of the face (it answered in space).
// `hint` as for SizeQuery::at.
int limit_at(const SizeQuery& q, const BackgroundMesh& bg, const SizeMap& m, int face, const Vec2& uv,
             const Vec3& xyz, int& hint);

}  // namespace sizemesh
