// The repair's trial sewing of a list of faces (sew, cad/sew_faces.h), which its caller may abandon.
#include "cad/sew_faces.h"

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressScope.hxx>

#include "cad/occt_model.h"

namespace sizemesh::detail {
namespace {

// Says "stop" once `flag` is set: a sewing no one waits for any more.
class FlagIndicator : public Message_ProgressIndicator {
 public:
  explicit FlagIndicator(const std::atomic<bool>& flag) : flag_(flag) {}
  Standard_Boolean UserBreak() override { return flag_.load(); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

 private:
  const std::atomic<bool>& flag_;
};

}  // namespace

Sewn sew(const FaceList& faces, double tol, const std::atomic<bool>* stop) {
  Sewn s;
  s.sewing = std::make_shared<BRepBuilderAPI_Sewing>(tol);
  for (const auto& f : faces) s.sewing->Add(f);
  if (stop) {
    Handle(FlagIndicator) indicator = new FlagIndicator(*stop);
    s.sewing->Perform(indicator->Start());
  } else {
    s.sewing->Perform();
  }
  s.shape = s.sewing->SewedShape();
  if (s.shape.IsNull()) s.shape = compound_of(faces);
  else mend_sewn_edges(s.shape, tol);
  s.free_curves = count_free_curves(s.shape);
  return s;
}

}  // namespace sizemesh::detail
