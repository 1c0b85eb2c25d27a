#include "app/batch.h"

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <glob.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "core/stopwatch.h"
#include "app/cli_options.h"

extern char** environ;

namespace sizemesh {
namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t g_stop = 0;  // the SIGINT or SIGTERM that arrived, 0 when none
void on_signal(int sig) { g_stop = sig; }

struct Job {
  std::string input, stem;
  pid_t pid = -1;
  Stopwatch clock;  // since the run started
  // The row of summary.csv.
  std::string status = "not run";
  int exit_code = -1;
  double seconds = 0, peak_mb = 0;
  long long triangles = -1, nodes = -1, bad = -1, avoidable = -1;
  std::string failed_faces, message;
};

bool is_cad(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs" || ext == ".brep";
}

// A folder's CAD files, or a glob pattern's matches, or the file itself.
std::vector<std::string> expand(const std::string& input) {
  std::vector<std::string> out;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    for (const auto& e : fs::directory_iterator(input, ec))
      if (e.is_regular_file(ec) && is_cad(e.path())) out.push_back(e.path().string());
  } else {
    glob_t g{};
    if (glob(input.c_str(), 0, nullptr, &g) == 0)
      for (size_t i = 0; i < g.gl_pathc; ++i) out.push_back(g.gl_pathv[i]);
    globfree(&g);
  }
  std::sort(out.begin(), out.end());
  if (out.empty()) throw Error("no CAD file matches '" + input + "'");
  return out;
}

// Output names: the file's stem, with a suffix where two inputs share one.
void name_outputs(std::vector<Job>& jobs) {
  std::set<std::string> used;
  for (Job& j : jobs) {
    const std::string stem = fs::path(j.input).stem().string();
    j.stem = stem;
    for (int k = 2; used.count(j.stem); ++k) j.stem = stem + "_" + std::to_string(k);
    used.insert(j.stem);
  }
}

// Starts one file's run: sizemesh FILE -q -o OUT --report JSON [options], stderr to its log.
pid_t start(const Job& j, const fs::path& out, const std::string& format, const std::vector<std::string>& extra) {
  // An earlier batch's files for this one must not pass for its results
  // (a run killed before writing its report would read the old one).
  std::error_code ec;
  for (const std::string& ext : {"." + format, std::string(".json"), std::string(".log")}) {
    fs::remove(out / (j.stem + ext), ec);
    for (int level = 1; level <= 8; ++level)  // a mesh family's levels (--family)
      fs::remove(out / (j.stem + ".L" + std::to_string(level) + ext), ec);
  }
  std::vector<std::string> args = {"/proc/self/exe", j.input, "-q", "-o", (out / (j.stem + "." + format)).string(),
                                   "--report", (out / (j.stem + ".json")).string()};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  const std::string log = (out / (j.stem + ".log")).string();
  posix_spawn_file_actions_addopen(&files, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int err = posix_spawn(&pid, "/proc/self/exe", &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  return err == 0 ? pid : -1;
}

// The row of a finished run, from its exit, its report and its log.
void finish(Job& j, int wstatus, const rusage& usage, bool timed_out, const fs::path& out) {
  j.seconds = j.clock.seconds();
  j.peak_mb = usage.ru_maxrss / 1024.0;
  const fs::path log = out / (j.stem + ".log");
  std::string last_line;
  {
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("sizemesh: error: ", 0) == 0) last_line = line.substr(17);
  }
  std::error_code ec;
  if (fs::exists(log, ec) && fs::file_size(log, ec) == 0) fs::remove(log, ec);
  if (timed_out) {
    j.status = "timeout", j.message = "killed after the time limit";
  } else if (WIFSIGNALED(wstatus)) {
    j.status = "crashed", j.message = std::string("signal ") + strsignal(WTERMSIG(wstatus));
  } else {
    j.exit_code = WEXITSTATUS(wstatus);
    j.status = j.exit_code == 0 ? "ok" : j.exit_code == 3 ? "partial" : "error";
    j.message = last_line;
  }
  if (j.status == "error") return;
  // One report, or a mesh family's (--family): the row has the finest
  // level's counts and the message each level's triangles.
  std::vector<fs::path> reports = {out / (j.stem + ".json")};
  if (!fs::exists(reports[0], ec)) {
    reports.clear();
    for (int level = 1; level <= 8 && fs::exists(out / (j.stem + ".L" + std::to_string(level) + ".json"), ec); ++level)
      reports.push_back(out / (j.stem + ".L" + std::to_string(level) + ".json"));
  }
  std::string levels;
  for (size_t i = 0; i < reports.size(); ++i) {
    std::ifstream report(reports[i]);
    try {
      const auto r = nlohmann::json::parse(report);
      const auto& m = r.at("mesh");
      j.triangles = m.at("triangles"), j.nodes = m.at("nodes");
      j.bad = m.at("bad_below_12deg"), j.avoidable = m.at("avoidable_below_12deg");
      j.failed_faces.clear();
      for (const auto& f : m.at("failed_faces"))
        j.failed_faces += (j.failed_faces.empty() ? "" : " ") + std::to_string(f.at("face").get<int>());
      if (reports.size() > 1)
        levels += (levels.empty() ? "family:" : ";") + std::string(" L") + std::to_string(i + 1) + " " +
                  std::to_string(j.triangles) + " triangles";
    } catch (const std::exception&) {  // a report cut short: the row keeps what the exit said
    }
  }
  if (!levels.empty()) j.message = j.message.empty() ? levels : j.message + "; " + levels;
}

std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

void write_summary(const fs::path& out, const std::vector<Job>& jobs) {
  std::ofstream f(out / "summary.csv");
  f << "file,status,exit_code,seconds,peak_mb,triangles,nodes,bad_below_12deg,avoidable_below_12deg,failed_faces,"
       "message\n";
  auto num = [](long long v) { return v < 0 ? std::string() : std::to_string(v); };
  for (const Job& j : jobs) {
    std::ostringstream sec, mb;
    sec.precision(3), mb.precision(4);
    sec << std::fixed << j.seconds;
    mb << std::fixed << j.peak_mb;
    f << csv(j.input) << "," << j.status << "," << (j.exit_code < 0 ? "" : std::to_string(j.exit_code)) << ","
      << sec.str() << "," << mb.str() << "," << num(j.triangles) << "," << num(j.nodes) << "," << num(j.bad) << ","
      << num(j.avoidable) << "," << csv(j.failed_faces) << "," << csv(j.message) << "\n";
  }
}

// Files done so far on stderr: in place on a terminal, a line per file otherwise.
void progress(bool quiet, int done, int total, int failed) {
  if (quiet) return;
  static const bool terminal = isatty(2);
  std::cerr << (terminal ? "\r" : "") << "batch: " << done << " / " << total << " files done (" << failed
            << " failed)" << (terminal && done < total ? "" : "\n") << std::flush;
}

// Runs the jobs, at most `parallel` at once; returns when all ended or a signal came.
void run_jobs(std::vector<Job>& jobs, const fs::path& out, const std::string& format,
              const std::vector<std::string>& extra, int parallel, double timeout, bool quiet) {
  std::map<pid_t, size_t> running;
  size_t next = 0;
  int done = 0, failed = 0;
  while ((next < jobs.size() || !running.empty()) && !g_stop) {
    while (next < jobs.size() && static_cast<int>(running.size()) < parallel) {
      Job& j = jobs[next];
      j.clock = Stopwatch();
      j.pid = start(j, out, format, extra);
      if (j.pid > 0) running[j.pid] = next;
      else j.status = "error", j.message = "could not start the sizemesh command", ++done, ++failed;
      ++next;
    }
    int wstatus = 0;
    rusage usage{};
    const pid_t pid = wait4(-1, &wstatus, WNOHANG, &usage);
    if (pid > 0 && running.count(pid)) {
      Job& j = jobs[running[pid]];
      running.erase(pid);
      finish(j, wstatus, usage, j.status == "timeout", out);
      ++done;
      failed += j.status != "ok";
      progress(quiet, done, static_cast<int>(jobs.size()), failed);
      continue;
    }
    for (auto& [p, k] : running)  // over time: killed, reaped on a later turn
      if (jobs[k].status != "timeout" && jobs[k].clock.seconds() > timeout)
        kill(p, SIGKILL), jobs[k].status = "timeout";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!g_stop) return;
  for (auto& [p, k] : running) kill(p, SIGTERM);  // interrupted: stop the children, keep what is done
  for (auto& [p, k] : running) {
    int wstatus = 0;
    rusage usage{};
    wait4(p, &wstatus, 0, &usage);
    jobs[k].status = "interrupted";
    jobs[k].seconds = jobs[k].clock.seconds();
  }
}

// The per-file options must be ones a single run takes: checked once, here.
void check_extra(const std::vector<std::string>& extra) {
  CLI::App app;
  RunCommandLine cl;
  add_run_options(app, cl);
  std::vector<std::string> args(extra.rbegin(), extra.rend());
  args.push_back("model.step");
  app.parse(args);
}

}  // namespace

int run_batch(int argc, char** argv) {
  // Options after "--" go to every file's run unchanged.
  std::vector<std::string> own, extra;
  bool after = false;
  for (int i = 1; i < argc; ++i) {
    if (!after && std::string(argv[i]) == "--") after = true;
    else (after ? extra : own).push_back(argv[i]);
  }
  CLI::App app{"sizemesh batch: meshes many CAD files, each in a process of its own, and writes OUTDIR/summary.csv "
               "with one row per file. Options after -- go to every file's run (see sizemesh --help).\n"
               "Exit status: 0 every file meshed, 1 nothing could start, 2 bad command line, 3 some file failed."};
  std::vector<std::string> inputs;
  std::string outdir, format = "vtu";
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  double timeout = 600;
  bool quiet = false;
  app.add_option("inputs", inputs, "CAD files, folders (their .step/.stp/.iges/.igs/.brep files) or glob patterns")
      ->required();
  app.add_option("-o,--output", outdir, "folder for the meshes, their reports and logs, and summary.csv")->required();
  app.add_option("-j,--jobs", jobs, "files meshed at once")->capture_default_str()->check(CLI::Range(1, 256));
  app.add_option("--format", format, "mesh format of every file")
      ->capture_default_str()->check(CLI::IsMember({"vtu", "msh", "stl", "cgns", "mesh", "smesh"}));
  app.add_option("--timeout", timeout, "seconds a file may take before it is stopped")
      ->capture_default_str()->check(CLI::Range(1.0, 1e7));
  app.add_flag("-q,--quiet", quiet, "no progress line");
  try {
    std::vector<std::string> args(own.rbegin(), own.rend());
    app.parse(args);
    check_extra(extra);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kUsage;
  }
  try {
    std::vector<Job> list;
    for (const std::string& in : inputs)
      for (const std::string& f : expand(in)) {
        list.emplace_back();
        list.back().input = f;
      }
    name_outputs(list);
    std::error_code ec;
    fs::create_directories(outdir, ec);
    if (!fs::is_directory(outdir)) throw Error("cannot create the output folder '" + outdir + "'");
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    run_jobs(list, outdir, format, extra, jobs, timeout, quiet);
    write_summary(outdir, list);
    if (g_stop) return 128 + g_stop;  // the shell's convention for a run stopped by a signal
    for (const Job& j : list)
      if (j.status != "ok") return kPartial;
    return kOk;
  } catch (const std::exception& e) {
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kError;
  }
}

}  // namespace sizemesh
