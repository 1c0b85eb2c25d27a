#include "io/cgns_writer.h"

#include <cgnslib.h>

#include <map>
#include <set>
#include <vector>

namespace sizemesh {

namespace {

// Closes the file on every path out; each failing call becomes one Error.
class CgnsFile {
 public:
  explicit CgnsFile(const std::string& path) : path_(path) {
    if (cg_open(path.c_str(), CG_MODE_WRITE, &fn_) != CG_OK) fail();
  }
  ~CgnsFile() {
    if (fn_ >= 0) cg_close(fn_);
  }
  int id() const { return fn_; }
  void check(int status) const {
    if (status != CG_OK) fail();
  }
  void close() {
    const int status = cg_close(fn_);
    fn_ = -1;
    check(status);
  }

 private:
  [[noreturn]] void fail() const { throw Error("cannot write '" + path_ + "': " + cg_get_error()); }
  std::string path_;
  int fn_ = -1;
};

LengthUnits_t length_unit(const std::string& unit) {
  if (unit == "m") return CGNS_ENUMV(Meter);
  if (unit == "cm") return CGNS_ENUMV(Centimeter);
  if (unit == "mm") return CGNS_ENUMV(Millimeter);
  if (unit == "ft") return CGNS_ENUMV(Foot);
  if (unit == "in") return CGNS_ENUMV(Inch);
  return CGNS_ENUMV(LengthUnitsNull);
}

BCType_t bc_type(Boundary kind) {
  switch (kind) {
    case Boundary::Farfield: return CGNS_ENUMV(BCFarfield);
    case Boundary::Symmetry: return CGNS_ENUMV(BCSymmetryPlane);
    case Boundary::Wall: break;
  }
  return CGNS_ENUMV(BCWall);
}

}  // namespace

void write_cgns(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels) {
  // Triangles grouped by marker, the groups in marker order.
  std::map<int, std::vector<int>> by_marker;
  for (size_t t = 0; t < m.tris.size(); ++t) by_marker[labels.marker_of(m.tri_face[t])].push_back(static_cast<int>(t));

  CgnsFile file(path);
  const int fn = file.id();
  int base = 0, zone = 0, coord = 0;
  file.check(cg_base_write(fn, "sizemesh", 2, 3, &base));  // triangles (cells of dimension 2) in 3D
  // Coordinates in the CAD file's unit: named where CGNS has a name for it.
  file.check(cg_goto(fn, base, "end"));
  const LengthUnits_t unit = length_unit(labels.unit);
  if (unit == CGNS_ENUMV(LengthUnitsNull)) {
    file.check(cg_dataclass_write(CGNS_ENUMV(NormalizedByUnknownDimensional)));
  } else {
    file.check(cg_dataclass_write(CGNS_ENUMV(Dimensional)));
    file.check(cg_units_write(CGNS_ENUMV(MassUnitsNull), unit, CGNS_ENUMV(TimeUnitsNull),
                              CGNS_ENUMV(TemperatureUnitsNull), CGNS_ENUMV(AngleUnitsNull)));
  }
  cgsize_t size[3] = {static_cast<cgsize_t>(m.xyz.size()), static_cast<cgsize_t>(m.tris.size()), 0};
  file.check(cg_zone_write(fn, base, "surface", size, CGNS_ENUMV(Unstructured), &zone));
  std::vector<double> c(m.xyz.size());
  const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < m.xyz.size(); ++i) c[i] = m.xyz[i][k];
    file.check(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), names[k], c.data(), &coord));
    const float length[5] = {0, 1, 0, 0, 0};  // mass, length, time, temperature, angle
    file.check(cg_goto(fn, base, "Zone_t", zone, "GridCoordinates", 0, "DataArray_t", coord, "end"));
    file.check(cg_exponents_write(CGNS_ENUMV(RealSingle), length));
  }

  // One Family_t per component (a user addresses a whole part) and per
  // marker, the latter with the boundary condition a solver applies to it.
  std::set<std::string> components;  // the far field and the symmetry plane are their own
  for (const auto& [marker, tris] : by_marker)
    if (labels.markers.at(marker).component != labels.markers.at(marker).name)
      components.insert(labels.markers.at(marker).component);
  for (const std::string& comp : components) {
    int fam = 0;
    file.check(cg_family_write(fn, base, comp.c_str(), &fam));
  }
  cgsize_t first = 1;
  for (const auto& [marker, tris] : by_marker) {
    const MeshLabels::Marker& mk = labels.markers.at(marker);
    // The marker's triangles, 1-based node ids, numbered on from the last section.
    std::vector<cgsize_t> conn;
    conn.reserve(3 * tris.size());
    for (int t : tris)
      for (int n : m.tris[t]) conn.push_back(n + 1);
    const cgsize_t last = first + static_cast<cgsize_t>(tris.size()) - 1;
    int section = 0, fam = 0, bc = 0, fambc = 0;
    file.check(cg_section_write(fn, base, zone, mk.name.c_str(), CGNS_ENUMV(TRI_3), first, last, 0, conn.data(),
                                &section));
    file.check(cg_family_write(fn, base, mk.name.c_str(), &fam));
    file.check(cg_fambc_write(fn, base, fam, "FamBC", bc_type(mk.kind), &fambc));
    // A boundary condition over the section's elements names the marker's
    // family and, as an additional family, its component's.
    cgsize_t range[2] = {first, last};
    file.check(cg_boco_write(fn, base, zone, mk.name.c_str(), CGNS_ENUMV(FamilySpecified), CGNS_ENUMV(PointRange), 2,
                             range, &bc));
    file.check(cg_boco_gridlocation_write(fn, base, zone, bc, CGNS_ENUMV(CellCenter)));
    file.check(cg_goto(fn, base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end"));
    file.check(cg_famname_write(mk.name.c_str()));
    if (mk.component != mk.name) file.check(cg_multifam_write("Component", mk.component.c_str()));
    first = last + 1;
  }
  file.close();
}

}  // namespace sizemesh
