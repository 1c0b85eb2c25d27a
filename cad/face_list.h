// Lists of faces for the preparation's steps: a shape's faces, a compound of them, two lists joined.
#pragma once

#include <BRep_Builder.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <vector>

namespace sizemesh::detail {

using FaceList = std::vector<TopoDS_Face>;

// The faces of `s`, each once.
inline FaceList faces_of(const TopoDS_Shape& s) {
  FaceList out;
  TopTools_IndexedMapOfShape fm;
  TopExp::MapShapes(s, TopAbs_FACE, fm);
  for (int i = 1; i <= fm.Extent(); ++i) out.push_back(TopoDS::Face(fm(i)));
  return out;
}

// The faces as one compound.
inline TopoDS_Compound compound_of(const FaceList& faces) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& f : faces) b.Add(c, f);
  return c;
}

// Faces of `faces` and of `more`.
inline FaceList joined(FaceList faces, const FaceList& more) {
  faces.insert(faces.end(), more.begin(), more.end());
  return faces;
}

}  // namespace sizemesh::detail
