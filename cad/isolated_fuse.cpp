// A general fuse run in a child process (fuse_in_child, cad/occt_model.h).
#include <BinTools.hxx>
#include <OSD_ThreadPool.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <filesystem>
#include <fstream>

#include "core/child_process.h"
#include "cad/deadline.h"
#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// A step as the child hands it back: its failure (a line, empty on success),
// how it ran out of time (a line, empty when it did not),
// the pocket faces, the pieces as (input face, result face) indices into the
// faces of `parts` and of the result, and the result shape (BinTools, exact).
bool write_step(const std::string& path, const FuseStep& s, const TopTools_IndexedMapOfShape& inputs) {
  std::ofstream out(path, std::ios::binary);
  TopTools_IndexedMapOfShape result;
  if (!s.shape.IsNull()) TopExp::MapShapes(s.shape, TopAbs_FACE, result);
  out << s.failure << "\n" << s.out_of_time << "\n" << s.worked << " " << s.pocket_faces << " " << s.pieces.size() << "\n";
  for (const auto& [from, to] : s.pieces) out << inputs.FindIndex(from) << " " << result.FindIndex(to) << "\n";
  out << (s.shape.IsNull() ? 0 : 1) << "\n";
  if (!s.shape.IsNull()) BinTools::Write(s.shape, out);
  return static_cast<bool>(out.flush());
}

FuseStep read_step(const std::string& path, const TopTools_IndexedMapOfShape& inputs) {
  FuseStep s;
  std::ifstream in(path, std::ios::binary);
  std::getline(in, s.failure);
  std::getline(in, s.out_of_time);
  size_t n = 0;
  in >> s.worked >> s.pocket_faces >> n;
  std::vector<std::pair<int, int>> pairs(n);
  for (auto& [i, j] : pairs) in >> i >> j;
  int has_shape = 0;
  in >> has_shape;
  in.get();  // the line's end
  if (!in) {
    s.failure = "the general fuse's result could not be read back";
    return s;
  }
  if (!has_shape) return s;
  BinTools::Read(s.shape, in);
  TopTools_IndexedMapOfShape result;
  TopExp::MapShapes(s.shape, TopAbs_FACE, result);
  for (const auto& [i, j] : pairs)
    if (i >= 1 && i <= inputs.Extent() && j >= 1 && j <= result.Extent())
      s.pieces.emplace_back(TopoDS::Face(inputs(i)), TopoDS::Face(result(j)));
  return s;
}

// OpenCASCADE's own thread pool (used by some checks inside the fuse) keeps
// its threads for the life of the process; a forked child would wait for
// them forever. Made with no worker thread before anything uses it, it runs
// its jobs on the calling thread, in the parent and in every child; made
// earlier by someone else, with threads, the child stays on one thread.
const bool kSerialPool = OSD_ThreadPool::DefaultPool(1)->NbThreads() == 1;

}  // namespace

FuseStep fuse_in_child(const std::vector<TopoDS_Shape>& parts, double seconds,
                       const std::function<FuseStep(bool parallel)>& here) {
  TopTools_IndexedMapOfShape inputs;
  for (const auto& p : parts) TopExp::MapShapes(p, TopAbs_FACE, inputs);
  const std::string path = child_result_path();
  // In the child, the work of `here` on the thread that runs it goes back with its result.
  const ChildOutcome outcome = run_in_child(
      [&](const std::string& file, bool threads) {
        double worked = 0;
        FuseStep s = timed(worked, [&] { return here(threads && kSerialPool); });
        s.worked = worked;
        return write_step(file, s, inputs);
      },
      kWallPerWork * seconds + 1.0, path);
  FuseStep out;
  switch (outcome) {
    case ChildOutcome::Done:
      try {
        out = read_step(path, inputs);
      } catch (const Standard_Failure& e) {
        out = FuseStep{};
        out.failure = std::string("the general fuse's result could not be read back: ") + e.GetMessageString();
      }
      break;
    case ChildOutcome::TimedOut:
      out.out_of_time = "did not end within its time and was stopped";
      out.failure = "the general fuse " + out.out_of_time;
      out.worked = seconds;  // all of it
      break;
    case ChildOutcome::Failed: out.failure = "the general fuse crashed"; break;
    case ChildOutcome::NoChild: out = here(true); break;
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
  return out;
}

}  // namespace sizemesh
