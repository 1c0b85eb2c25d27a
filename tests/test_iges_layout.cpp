// IGES parameter data past column 64 (pyGeo's layout) are re-wrapped, and pyGeo's wing meshes as a half model.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "cad/iges_layout.h"
#include "cad/model.h"
#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

// One IGES parameter line: 64 data columns (65 when `spill`), the pointer, P, the sequence.
std::string p_line(const std::string& data, int pointer, int seq, bool spill) {
  char tail[32];
  std::snprintf(tail, sizeof tail, spill ? "%7dP%7d" : "%8dP%7d", pointer, seq);
  return data + std::string((spill ? 65 : 64) - data.size(), ' ') + tail;
}

std::string line(const std::string& data, char section, int seq) {
  char tail[16];
  std::snprintf(tail, sizeof tail, "%c%7d", section, seq);
  return data + std::string(72 - data.size(), ' ') + tail;
}

}  // namespace

TEST_CASE("IGES parameter data in column 65 are re-wrapped to 64 columns with pointers and counts updated") {
  // A point (type 116) whose data run to column 65 (the delimiter there), as pyGeo writes.
  const std::string spilled = std::string(53, ' ') + "116,1.5,2.5,";
  REQUIRE(spilled.size() == 65);
  std::string file = line("", 'S', 1) + "\n" + line("1H,,1H;;", 'G', 1) + "\n" +
                     line("     116       1       0       0       0       0       0       000000001", 'D', 1) + "\n" +
                     line("     116       0       0       2       0", 'D', 2) + "\n" +
                     p_line(spilled, 1, 1, true) + "\n" + p_line("3.25;", 1, 2, false) + "\n" +
                     line("S      1G      1D      2P      2", 'T', 1) + "\n";
  const auto fixed = realign_iges_parameters(file);
  REQUIRE(fixed);
  CHECK(fixed->lines_moved == 1);
  // The data read back: "116,1.5,2.5,3.25;" on one line, pointer 1, sequence 1.
  const std::string expect_p = "116,1.5,2.5,3.25;" + std::string(47, ' ') + "       1P      1";
  CHECK(fixed->text.find(expect_p + "\n") != std::string::npos);
  // The directory entry counts one parameter line; the terminate record one P line.
  CHECK(fixed->text.find("     116       0       0       1       0") != std::string::npos);
  CHECK(fixed->text.find("S      1G      1D      2P      1") != std::string::npos);
  // A file laid out as the standard asks is left alone.
  CHECK_FALSE(realign_iges_parameters(fixed->text));
}

TEST_CASE("the pyGeo IGES wing is read with one warning line and meshed as a half model") {
  const test::TempDir dir("union_iges");
  const std::string out = (dir / "c172.vtu");
  const auto r = test::run_sizemesh(test::model_path("c172_wing_pygeo.igs") + " -q -o " + out);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err_lines() == 2);
  CHECK(r.err.find("12 IGES parameter lines have data in column 65") != std::string::npos);
  CHECK(r.err.find("a half model, open on the plane z = 0") != std::string::npos);
  const Model m = load_model(test::model_path("c172_wing_pygeo.igs"));
  CHECK(m.num_faces() == 6);
  CHECK(m.info().entities_failed == 0);
  // A half wing: its root airfoil (two curves, on z = 0) is all that stays open.
  CHECK(m.info().free_curves_after_sewing == 2);
  CHECK(m.info().preparation.half_model_axis == 2);
  CHECK(m.info().preparation.caps_added == 0);
}
