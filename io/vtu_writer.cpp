#include "io/vtu_writer.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>
#include <fstream>

namespace sizemesh {

namespace {
vtkNew<vtkDoubleArray> make_array(const Field& f) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(f.first.c_str());
  a->SetNumberOfValues(static_cast<vtkIdType>(f.second.size()));
  for (size_t i = 0; i < f.second.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), f.second[i]);
  return a;
}
}  // namespace

void write_vtu(const std::string& path, const std::vector<Vec3>& xyz,
               const std::vector<std::array<int, 3>>& tris, const std::vector<Field>& point_data,
               const std::vector<Field>& cell_data) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(xyz.size()));
  for (size_t i = 0; i < xyz.size(); ++i) points->SetPoint(static_cast<vtkIdType>(i), xyz[i].data());
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(static_cast<vtkIdType>(tris.size()));
  for (const auto& t : tris) {
    vtkIdType ids[3] = {t[0], t[1], t[2]};
    grid->InsertNextCell(VTK_TRIANGLE, 3, ids);
  }
  for (const Field& f : point_data) grid->GetPointData()->AddArray(make_array(f));
  for (const Field& f : cell_data) grid->GetCellData()->AddArray(make_array(f));
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  // zlib, not LZ4: ParaView, meshio and every VTK reader take it; level 1 keeps it fast.
  writer->SetCompressorTypeToZLib();
  writer->SetCompressionLevel(1);
  if (writer->Write() != 1) throw Error("cannot write '" + path + "'");
}

void check_writable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error("output path '" + path + "' is a directory");
  const bool existed = fs::exists(path, ec);
  {
    std::ofstream probe(path, std::ios::app);
    if (!probe) throw Error("cannot write output file '" + path + "'");
  }
  if (!existed) fs::remove(path, ec);
}

}  // namespace sizemesh
