// Runs the sizemesh command in a shell and captures exit status and output.
#pragma once

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace sizemesh::test {

struct CommandResult {
  int status = -1;       // exit status; -1 when killed by a signal
  std::string out, err;  // standard output and error
  int err_lines() const {
    int n = 0;
    for (char c : err) n += c == '\n';
    return n;
  }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// timeout_s > 0: the run is killed after that many seconds (its status is then not 0-3).
inline CommandResult run_sizemesh(const std::string& args, int timeout_s = 0) {
  static int counter = 0;
  const std::string base = "/tmp/sizemesh_cli_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::string limit = timeout_s > 0 ? "timeout -s KILL " + std::to_string(timeout_s) + " " : "";
  const std::string cmd = limit + SIZEMESH_BINARY + " " + args + " </dev/null >" + base + ".out 2>" + base + ".err";
  const int raw = std::system(cmd.c_str());
  CommandResult r;
  if (WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

// Runs sizemesh with args and `--report report`; the run must end with exit
// status `expected` (its stderr is shown if not). Returns the parsed report.
inline nlohmann::json run_with_report(const std::string& args, const std::string& report, int expected = 0) {
  const CommandResult r = run_sizemesh(args + " --report " + report);
  INFO(r.err);
  REQUIRE(r.status == expected);
  return nlohmann::json::parse(slurp(report));
}

}  // namespace sizemesh::test
