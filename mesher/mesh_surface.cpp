// The surface mesher's top level (paper 4.1): curves, then every face in parallel, then assembly.
//
// One face's meshing is in face_strategies.cpp; the repairs of faces meshed
// back to back (drop_back_to_back, flip_shared_inner_edges) in back_to_back.cpp.
#include "mesher/mesh_surface.h"

#include <algorithm>
#include <atomic>
#include <numeric>

#include <tbb/task_arena.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/stopwatch.h"
#include "mesher/discretise_curves.h"
#include "mesher/face_strategies.h"

namespace sizemesh {
namespace {

using mesh_surface_detail::FaceResult;
using mesh_surface_detail::mesh_face;

// The stages, in the arena mesh_surface() sets up.
SurfaceMesh mesh_in_arena(const Geometry& g, const SizeField& h, const MeshOptions& o) {
  SurfaceMesh out;
  // 1. Curves: one unit mesh per curve (paper 2.1), shared by its faces.
  Stopwatch clock;
  CurveMesh cm;
  try {
    cm = discretise_curves(g, h);
  } catch (const Error&) {  // nothing can be meshed without the curves
    for (int f = 1; f <= g.num_faces(); ++f)
      out.failures.push_back({f, "the curves could not be discretised (geometry kernel error)"});
    return out;
  }
  out.stats.seconds_curves = clock.lap();
  out.stats.size_queries += cm.size_queries;

  // 2. Faces: independent once the curves are fixed.
  const int nf = g.num_faces();
  std::vector<FaceResult> faces(nf + 1);
  // Largest expected first, each thread taking the next face as it comes
  // free (longest-processing-time order): a dominant face starts at once
  // instead of behind the faces before it in a chunk. Faces are independent,
  // so the mesh is the same for any order and thread count.
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 1);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return o.expected(a) > o.expected(b); });
  std::atomic<int> done{0}, next{0};
  const int workers = std::min(nf, tbb::this_task_arena::max_concurrency());
  tbb::parallel_for(
      0, workers,
      [&](int) {
        for (int i; (i = next++) < nf;) {
          const int f = order[i];
          faces[f] = mesh_face(g, h, cm, f, o);
          if (o.on_face_done) o.on_face_done(++done, nf);
        }
      },
      tbb::simple_partitioner());
  out.stats.seconds_faces = clock.lap();

  // 3. Assembly in face order: shared nodes by index, inner nodes appended.
  out.xyz = std::move(cm.xyz);
  out.node_dim = std::move(cm.node_dim);
  out.node_entity = std::move(cm.node_entity);
  for (int f = 1; f <= nf; ++f) {
    FaceResult& r = faces[f];
    out.stats.size_queries += r.size_queries;
    out.stats.fronts_3d += r.fronts_3d;
    out.stats.front_steps += r.front_steps;
    out.stats.front_work += r.front_work;
    out.stats.faces_retried += r.strategy > 0;
    out.stats.faces_relaxed += r.strategy >= 2;
    out.stats.faces_lenient += r.lenient;
    out.stats.faces_filled += r.filled;
    out.stats.seconds_front += r.seconds_front;
    out.stats.seconds_optimise += r.seconds_optimise;
    out.stats.evaluations_setup += r.evaluations_setup;
    out.stats.evaluations_front += r.evaluations_front;
    out.stats.evaluations_optimise += r.evaluations_optimise;
    if (!r.ok) {
      out.failures.push_back({f, r.reason});
      continue;
    }
    const FaceMesh& fm = r.mesh;
    std::vector<int> id(fm.num_nodes(), -1);
    for (int i = 0; i < fm.num_nodes(); ++i) {
      if (fm.global[i] >= 0) {
        id[i] = fm.global[i];
        continue;
      }
      id[i] = static_cast<int>(out.xyz.size());
      out.xyz.push_back(fm.s[i].p);
      out.node_dim.push_back(2);
      out.node_entity.push_back(f);
    }
    const bool flip = g.face_reversed(f);
    for (const auto& t : fm.tris) {
      if (fm.pole_triangle(t)) continue;  // zero area on a pole
      std::array<int, 3> gt{id[t[0]], id[t[1]], id[t[2]]};
      std::array<Vec2, 3> uv{fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]};
      if (flip) {
        std::swap(gt[1], gt[2]);
        std::swap(uv[1], uv[2]);
      }
      out.tris.push_back(gt);
      out.tri_face.push_back(f);
      out.tri_uv.push_back(uv);
    }
  }
  drop_back_to_back(out);
  flip_shared_inner_edges(out);
  return out;
}

}  // namespace

SurfaceMesh mesh_surface(const Geometry& g, const SizeField& h, const MeshOptions& o) {
  // A local arena: the thread count applies to this call only.
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  SurfaceMesh out;
  arena.execute([&] { out = mesh_in_arena(g, h, o); });
  return out;
}

}  // namespace sizemesh
