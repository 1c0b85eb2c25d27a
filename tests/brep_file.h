// Shapes built in a test, written as one .brep file that sizemesh reads.
#pragma once

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>
#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace sizemesh::test {

// The shapes in one compound, written at `path`; returns `path`.
inline std::string write_compound(const std::vector<TopoDS_Shape>& shapes, const std::string& path) {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  for (const auto& s : shapes) b.Add(c, s);
  REQUIRE(BRepTools::Write(c, path.c_str()));
  return path;
}

}  // namespace sizemesh::test
