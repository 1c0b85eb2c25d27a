// CGNS output read back with the CGNS library's own reader (and checked by
// its cgnscheck, installed by cmake/setup.sh): counts, element sections named
// after the markers, families with their boundary conditions, one family per
// component on the F-16.
#include <catch2/catch.hpp>

#include <cgnslib.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

namespace fs = std::filesystem;
using sizemesh::test::run_sizemesh;

namespace {

struct CgnsContents {
  int cell_dim = 0, phys_dim = 0;
  long nodes = 0, cells = 0;
  std::map<std::string, std::pair<long, long>> sections;  // name -> element range
  std::vector<long> connectivity;                          // all sections, in order
  std::map<std::string, BCType_t> families;                // name -> FamilyBC (BCTypeNull when none)
  std::map<std::string, std::string> bc_family;            // BC name -> its FamilyName
  std::map<std::string, std::string> bc_component;         // BC name -> its additional family
};

CgnsContents read_cgns(const std::string& path) {
  CgnsContents c;
  int fn = -1;
  REQUIRE(cg_open(path.c_str(), CG_MODE_READ, &fn) == CG_OK);
  int nbases = 0;
  REQUIRE(cg_nbases(fn, &nbases) == CG_OK);
  REQUIRE(nbases == 1);
  char name[33];
  REQUIRE(cg_base_read(fn, 1, name, &c.cell_dim, &c.phys_dim) == CG_OK);
  int nzones = 0;
  REQUIRE(cg_nzones(fn, 1, &nzones) == CG_OK);
  REQUIRE(nzones == 1);
  cgsize_t size[3];
  REQUIRE(cg_zone_read(fn, 1, 1, name, size) == CG_OK);
  c.nodes = size[0];
  c.cells = size[1];
  int nsections = 0;
  REQUIRE(cg_nsections(fn, 1, 1, &nsections) == CG_OK);
  for (int s = 1; s <= nsections; ++s) {
    ElementType_t type;
    cgsize_t first, last;
    int nbndry, parent;
    REQUIRE(cg_section_read(fn, 1, 1, s, name, &type, &first, &last, &nbndry, &parent) == CG_OK);
    CHECK(type == CGNS_ENUMV(TRI_3));
    c.sections[name] = {first, last};
    std::vector<cgsize_t> conn(3 * (last - first + 1));
    REQUIRE(cg_elements_read(fn, 1, 1, s, conn.data(), nullptr) == CG_OK);
    c.connectivity.insert(c.connectivity.end(), conn.begin(), conn.end());
  }
  int nfam = 0;
  REQUIRE(cg_nfamilies(fn, 1, &nfam) == CG_OK);
  for (int f = 1; f <= nfam; ++f) {
    int nbc = 0, ngeo = 0;
    REQUIRE(cg_family_read(fn, 1, f, name, &nbc, &ngeo) == CG_OK);
    BCType_t bc = CGNS_ENUMV(BCTypeNull);
    char bcname[33];
    if (nbc > 0) REQUIRE(cg_fambc_read(fn, 1, f, 1, bcname, &bc) == CG_OK);
    c.families[name] = bc;
  }
  int nbocos = 0;
  REQUIRE(cg_nbocos(fn, 1, 1, &nbocos) == CG_OK);
  for (int b = 1; b <= nbocos; ++b) {
    BCType_t type;
    PointSetType_t set;
    cgsize_t npts, normal_list;
    int normal_index[3], ndataset;
    DataType_t normal_type;
    REQUIRE(cg_boco_info(fn, 1, 1, b, name, &type, &set, &npts, normal_index, &normal_list, &normal_type, &ndataset) ==
            CG_OK);
    CHECK(type == CGNS_ENUMV(FamilySpecified));
    const std::string bc = name;
    REQUIRE(cg_goto(fn, 1, "Zone_t", 1, "ZoneBC_t", 1, "BC_t", b, "end") == CG_OK);
    char family[33];
    if (cg_famname_read(family) == CG_OK) c.bc_family[bc] = family;
    int nmulti = 0;
    if (cg_nmultifam(&nmulti) == CG_OK && nmulti > 0) {
      char label[33], fam[33];
      REQUIRE(cg_multifam_read(1, label, fam) == CG_OK);
      c.bc_component[bc] = fam;
    }
  }
  cg_close(fn);
  return c;
}

std::string cgnscheck(const std::string& path) {
  const std::string log = path + ".check";
  std::system(("cgnscheck " + path + " >" + log + " 2>&1").c_str());
  return sizemesh::test::slurp(log);
}

}  // namespace

TEST_CASE("CGNS of the M6 in a half far field: counts, sections, families and boundary conditions", "[cgns]") {
  sizemesh::test::TempDir dir("cgns_m6");
  const auto report = sizemesh::test::run_with_report(sizemesh::test::model_path("onera_m6_wing.stp") +
                                                          " -q --farfield sphere --symmetry y -o " + (dir / "m6.cgns"),
                                                      dir / "m6.json");
  const CgnsContents c = read_cgns(dir / "m6.cgns");
  CHECK(c.cell_dim == 2);
  CHECK(c.phys_dim == 3);
  CHECK(c.nodes == report["mesh"]["nodes"].get<long>());
  CHECK(c.cells == report["mesh"]["triangles"].get<long>());
  // The wing's faces but its root (face 9, on the symmetry plane), the far field and the plane.
  std::set<std::string> expected;
  for (int f : {1, 2, 3, 4, 5, 6, 7, 8, 10, 11}) expected.insert("face_" + std::to_string(f));
  expected.insert("farfield");
  expected.insert("symmetry");
  std::set<std::string> sections;
  long covered = 0, next = 1;
  for (const auto& [name, range] : c.sections) sections.insert(name);
  CHECK(sections == expected);
  // Element ranges follow each other from 1 to the last triangle.
  std::map<long, long> ranges;
  for (const auto& [name, range] : c.sections) ranges[range.first] = range.second;
  for (const auto& [first, last] : ranges) {
    CHECK(first == next);
    covered += last - first + 1;
    next = last + 1;
  }
  CHECK(covered == c.cells);
  long out_of_range = 0;
  for (long n : c.connectivity) out_of_range += n < 1 || n > c.nodes;
  CHECK(out_of_range == 0);
  CHECK(static_cast<long>(c.connectivity.size()) == 3 * c.cells);
  // Families: one per marker with its boundary condition, and the wing's component.
  for (const std::string& name : expected) {
    INFO(name);
    REQUIRE(c.families.count(name));
    const BCType_t want = name == "farfield"   ? CGNS_ENUMV(BCFarfield)
                          : name == "symmetry" ? CGNS_ENUMV(BCSymmetryPlane)
                                               : CGNS_ENUMV(BCWall);
    CHECK(c.families.at(name) == want);
    CHECK(c.bc_family.at(name) == name);
    if (name.rfind("face_", 0) == 0) CHECK(c.bc_component.at(name) == "component_1");
  }
  CHECK(c.families.count("component_1"));
  CHECK(c.families.size() == expected.size() + 1);
  INFO("cgnscheck is installed by bash cmake/setup.sh (Debian package cgns-convert)");
  REQUIRE(std::system("command -v cgnscheck >/dev/null 2>&1") == 0);
  const std::string check = cgnscheck(dir / "m6.cgns");
  INFO(check);
  CHECK(check.find("checking complete") != std::string::npos);
  CHECK(check.find("ERROR") == std::string::npos);
  CHECK(check.find("WARNING") == std::string::npos);
}

TEST_CASE("CGNS of the F-16's wetted surface lists one family per component", "[cgns]") {
  sizemesh::test::TempDir dir("cgns_f16");
  const auto report = sizemesh::test::run_with_report(
      sizemesh::test::model_path("f16_openvsp.stp") + " -q -o " + (dir / "f16.cgns"), dir / "f16.json");
  const CgnsContents c = read_cgns(dir / "f16.cgns");
  CHECK(c.cells == report["mesh"]["triangles"].get<long>());
  // The seven components after sewing all have faces on the wetted surface.
  const size_t components = report["preparation"]["components"].size();
  REQUIRE(components == 7);
  std::set<std::string> component_families, referenced;
  for (const auto& [name, bc] : c.families)
    if (name.rfind("component_", 0) == 0) component_families.insert(name);
  for (const auto& [bc, comp] : c.bc_component) referenced.insert(comp);
  CHECK(component_families.size() == components);
  CHECK(referenced == component_families);
  CHECK(c.sections.size() + components == c.families.size());
  const std::string check = cgnscheck(dir / "f16.cgns");
  INFO(check);
  CHECK(check.find("ERROR") == std::string::npos);
}

TEST_CASE("a CGNS file that cannot be written gives one line", "[cgns]") {
  const auto r = run_sizemesh(sizemesh::test::model_path("onera_m6_wing.stp") + " -q -o /nonexistent_dir/x.cgns");
  CHECK(r.status == 1);
  CHECK(r.err_lines() == 1);
  CHECK(r.err.find("cannot write") != std::string::npos);
}
