// An independent check of the wetted surface: TetGen (Debian `tetgen`,
// installed by cmake/setup.sh) builds a volume mesh only from a closed surface
// that does not intersect itself. The shared OpenVSP aircraft, written as STL
// by sizemesh at default settings, must be accepted.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/cli_runner.h"
#include "tests/test_models.h"

namespace fs = std::filesystem;

namespace {

// TetGen reads ASCII STL only; sizemesh writes binary STL. Returns the
// number of triangles converted.
long ascii_stl(const std::string& binary, const std::string& ascii) {
  std::ifstream in(binary, std::ios::binary);
  char header[80];
  uint32_t n = 0;
  if (!in.read(header, 80) || !in.read(reinterpret_cast<char*>(&n), 4)) return -1;
  std::ofstream out(ascii);
  out.precision(9);  // every float exactly
  out << "solid sizemesh\n";
  for (uint32_t i = 0; i < n; ++i) {
    char rec[50];
    if (!in.read(rec, 50)) return -1;
    float v[12];
    std::memcpy(v, rec, sizeof v);
    out << "facet normal " << v[0] << " " << v[1] << " " << v[2] << "\n outer loop\n";
    for (int k = 1; k <= 3; ++k) out << "  vertex " << v[3 * k] << " " << v[3 * k + 1] << " " << v[3 * k + 2] << "\n";
    out << " endloop\nendfacet\n";
  }
  out << "endsolid sizemesh\n";
  return static_cast<long>(n);
}

}  // namespace

TEST_CASE("tetgen builds a volume mesh inside the shared aircraft's wetted surfaces", "[models]") {
  INFO("tetgen is installed by bash cmake/setup.sh (Debian package tetgen)");
  REQUIRE(std::system("command -v tetgen >/dev/null 2>&1") == 0);
  for (const char* file : {"f16_openvsp.stp", "manta2_openvsp.stp", "transport_wbnp_openvsp.stp"}) {
    SECTION(file) {
      const fs::path dir = fs::temp_directory_path() / ("sizemesh_tetgen_" + std::to_string(::getpid()));
      fs::create_directories(dir);
      const std::string stl = (dir / "surface.stl").string(), ascii = (dir / "wetted.stl").string();
      const auto r = sizemesh::test::run_sizemesh(sizemesh::test::model_path(file) + " -q -o " + stl);
      INFO(r.err);
      REQUIRE(r.status == 0);
      REQUIRE(ascii_stl(stl, ascii) > 1000);
      // -p: tetrahedralise a piecewise linear complex; -Y: keep the surface
      // as given; -Q: quiet. TetGen stops with an error on an open or
      // self-intersecting surface.
      const std::string cmd = "cd " + dir.string() + " && timeout 300 tetgen -pYQ wetted.stl >tetgen.log 2>&1";
      INFO(sizemesh::test::slurp((dir / "tetgen.log").string()));
      CHECK(std::system(cmd.c_str()) == 0);
      CHECK(fs::exists(dir / "wetted.1.ele"));
      CHECK(fs::file_size(dir / "wetted.1.ele") > 1000);
      fs::remove_all(dir);
    }
  }
}
