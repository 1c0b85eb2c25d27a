// The "From CAD to a volume mesh" commands of docs/formats.md, run as they
// stand (from a copy of the repository's examples and the built binary), so
// that they cannot go stale: TetGen, Gmsh and the CGNS checker must all accept
// what sizemesh writes. And the README, the front door, links every file of
// docs/ and only files that exist.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "tests/cli_runner.h"

namespace fs = std::filesystem;

namespace {

// The indented lines between the two markers of a Markdown file.
std::string command_block(const std::string& readme) {
  const std::string begin = "<!-- volume-mesh commands", end = "<!-- end of volume-mesh commands -->";
  const size_t a = readme.find(begin), b = readme.find(end);
  if (a == std::string::npos || b == std::string::npos || b < a) return {};
  std::string block, line;
  std::istringstream in(readme.substr(a, b - a));
  std::getline(in, line);  // the opening marker
  while (std::getline(in, line))
    if (line.rfind("    ", 0) == 0) block += line.substr(4) + "\n";
  return block;
}

}  // namespace

TEST_CASE("the documented commands from STEP to TetGen, Gmsh and CGNS volume inputs run as written", "[readme]") {
  const std::string block = command_block(sizemesh::test::slurp(SIZEMESH_DOCS "/formats.md"));
  REQUIRE(block.find("tetgen") != std::string::npos);
  REQUIRE(block.find("gmsh") != std::string::npos);
  REQUIRE(block.find("cgnscheck") != std::string::npos);
  // A scratch copy of the layout the commands expect: ./build/sizemesh and examples/.
  const fs::path dir = fs::temp_directory_path() / ("sizemesh_readme_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "build");
  fs::create_symlink(SIZEMESH_BINARY, dir / "build" / "sizemesh");
  fs::create_symlink(fs::canonical(SIZEMESH_EXAMPLES_DIR), dir / "examples");
  {
    std::ofstream script(dir / "commands.sh");
    script << "set -e\n" << block;
  }
  const std::string cmd = "cd " + dir.string() + " && timeout 600 bash commands.sh >log.txt 2>&1";
  const int status = std::system(cmd.c_str());
  INFO(block << "\n" << sizemesh::test::slurp((dir / "log.txt").string()));
  REQUIRE(status == 0);
  for (const char* out : {"m6.1.ele", "m6.1.face", "m6_volume.msh", "m6.cgns"}) {
    INFO(out);
    CHECK(fs::exists(dir / out));
    CHECK(fs::file_size(dir / out) > 1000);
  }
  fs::remove_all(dir);
}

TEST_CASE("the README links every file of docs/, each link resolves, and it stays short", "[readme]") {
  const std::string readme = sizemesh::test::slurp(SIZEMESH_README);
  REQUIRE(!readme.empty());
  CHECK(std::count(readme.begin(), readme.end(), '\n') <= 170);
  // Every Markdown file of docs/ is linked from the README ...
  std::set<std::string> docs;
  for (const auto& entry : fs::directory_iterator(SIZEMESH_DOCS))
    if (entry.path().extension() == ".md") docs.insert(entry.path().filename().string());
  CHECK(docs.count("options.md") == 1);
  CHECK(docs.count("formats.md") == 1);
  for (const std::string& name : docs) {
    INFO(name);
    CHECK(readme.find("](docs/" + name + ")") != std::string::npos);
  }
  // ... and every docs/*.md the README links exists.
  const std::string link = "](docs/";
  for (size_t at = readme.find(link); at != std::string::npos; at = readme.find(link, at + 1)) {
    const size_t end = readme.find(')', at);
    const std::string target = readme.substr(at + 2, end - at - 2);
    if (target.size() < 3 || target.compare(target.size() - 3, 3, ".md") != 0) continue;  // the picture
    INFO(target);
    CHECK(fs::exists(fs::path(SIZEMESH_DOCS) / target.substr(5)));
  }
}
