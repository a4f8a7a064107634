// quakeview-prep under stress: an OSM file whose building ways reference hundreds of thousands of
// missing nodes, writes that fail part-way (RLIMIT_FSIZE makes the kernel refuse writes past a
// size, as a full disk does), and SIGINT (Ctrl-C) during a long run. In each case: a clear message,
// exit code 1, and the previous output left exactly as it was (nothing half-written beside it).
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;

struct Run {
  int exitCode = -1;
  int signal = 0;
  std::string output;  // stdout and stderr
};

struct Limits {
  rlim_t fileSizeBytes = RLIM_INFINITY;
  int interruptAfterMs = -1;  // SIGINT after this long (< 0: never)
};

/// Runs the tool with `args`, stdout and stderr captured together.
Run runTool(const std::vector<std::string>& args, const Limits& limits = {}) {
  int pipeFds[2];
  REQUIRE(pipe(pipeFds) == 0);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    dup2(pipeFds[1], 1);
    dup2(pipeFds[1], 2);
    close(pipeFds[0]);
    close(pipeFds[1]);
    if (limits.fileSizeBytes != RLIM_INFINITY) {
      // Past the limit write() fails with EFBIG instead of the process being killed by SIGXFSZ.
      signal(SIGXFSZ, SIG_IGN);
      const rlimit limit{limits.fileSizeBytes, limits.fileSizeBytes};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kTool.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(kTool.c_str(), argv.data());
    _exit(127);
  }
  close(pipeFds[1]);
  std::thread interrupter;
  if (limits.interruptAfterMs >= 0) {
    interrupter = std::thread([pid, ms = limits.interruptAfterMs] {
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      kill(pid, SIGINT);
    });
  }
  Run r;
  char buffer[4096];
  ssize_t n = 0;
  while ((n = read(pipeFds[0], buffer, sizeof buffer)) > 0) r.output.append(buffer, static_cast<std::size_t>(n));
  close(pipeFds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (interrupter.joinable()) interrupter.join();
  if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("quakeview-stress-" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

/// Every file under `dir` with its size (to compare a directory before and after).
std::vector<std::pair<std::string, std::uintmax_t>> listing(const fs::path& dir) {
  std::vector<std::pair<std::string, std::uintmax_t>> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.emplace_back(fs::relative(e.path(), dir).string(), e.file_size());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Nothing beside `target` but the target itself (no staging or old directories left behind).
bool noLeftovers(const fs::path& target) {
  for (const auto& e : fs::directory_iterator(target.parent_path())) {
    const std::string name = e.path().filename().string();
    if (name != target.filename().string() && name.rfind(target.filename().string(), 0) == 0) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("An OSM file whose buildings reference hundreds of thousands of missing nodes is refused clearly",
          "[prep][stress]") {
  const fs::path dir = scratch("missing-nodes");
  fs::create_directories(dir);
  const fs::path osm = dir / "broken.osm";
  {
    // 100,000 closed building ways over 400,000 node references, only the first 1,000 nodes present.
    std::ofstream out(osm);
    out << "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\" generator=\"test\">\n";
    for (int n = 1; n <= 1000; ++n) {
      out << " <node id=\"" << n << "\" lat=\"" << 40.70 + n * 1e-5 << "\" lon=\"" << -74.0 + (n % 37) * 1e-5
          << "\"/>\n";
    }
    for (int w = 1; w <= 100000; ++w) {
      const long base = 1 + (static_cast<long>(w) * 3) % 400000;
      out << " <way id=\"" << w << "\"><nd ref=\"" << base << "\"/><nd ref=\"" << base + 1 << "\"/><nd ref=\""
          << base + 2 << "\"/><nd ref=\"" << base << "\"/><tag k=\"building\" v=\"yes\"/></way>\n";
    }
    out << "</osm>\n";
  }
  const fs::path city = dir / "city";
  const auto started = std::chrono::steady_clock::now();
  const Run r = runTool({"city", "--input", osm.string(), "--out", city.string()});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find(osm.string()) != std::string::npos);
  CHECK(r.output.find("missing from the file") != std::string::npos);
  CHECK(r.output.find("first: n") != std::string::npos);  // names the first missing nodes
  CHECK(r.output.find("osmium extract --strategy complete_ways") != std::string::npos);
  CHECK_FALSE(fs::exists(city));
  CHECK(noLeftovers(city));
  CHECK(seconds < 120.0);  // a refusal, not a hang (generous: sanitizer builds are slow)
  fs::remove_all(dir);
}

TEST_CASE("Writes that fail part-way (a full disk) are errors and leave the previous city intact", "[prep][stress]") {
  const fs::path city = scratch("full-disk");
  const Run first = runTool(
      {"synth-city", "--buildings", "3000", "--seed", "3", "--max-leaf-buildings", "200", "--out", city.string()});
  REQUIRE(first.exitCode == 0);
  const auto before = listing(city);
  REQUIRE(before.size() > 10);

  // Another city into the same place, but no file may grow past 64 KiB: some tile write fails.
  const Run r = runTool(
      {"synth-city", "--buildings", "3000", "--seed", "4", "--max-leaf-buildings", "200", "--out", city.string()},
      Limits{64 * 1024, -1});
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.signal == 0);
  CHECK(r.output.find("cannot write") != std::string::npos);
  CHECK(r.output.find("File too large") != std::string::npos);  // the system's reason, as it said it
  CHECK(listing(city) == before);                               // the previous city, byte counts and all
  CHECK(noLeftovers(city));

  // And the response of that city: the manifest is rewritten last, so a failed write leaves it.
  const Run resp = runTool({"response", "--city", city.string(), "--synthetic", "1"}, Limits{16 * 1024, -1});
  INFO(resp.output);
  CHECK(resp.exitCode == 1);
  CHECK(resp.output.find("cannot write") != std::string::npos);
  std::ifstream manifest(city / "tileset.json");
  const std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
  CHECK(text.find("\"response\"") == std::string::npos);  // still the city without results
  const Run verify = runTool({"info", city.string(), "--verify"});
  CHECK(verify.exitCode == 0);
  fs::remove_all(city.parent_path());
}

TEST_CASE("Ctrl-C during a long run stops it with a message and leaves no partial output", "[prep][stress]") {
  const fs::path city = scratch("interrupted");
  const Run first = runTool({"synth-city", "--buildings", "2000", "--seed", "1", "--out", city.string()});
  REQUIRE(first.exitCode == 0);
  const auto before = listing(city);

  // A million buildings take far longer than the half second before the interrupt.
  const Run r = runTool({"synth-city", "--buildings", "1000000", "--seed", "2", "--out", city.string()},
                        Limits{RLIM_INFINITY, 500});
  INFO(r.output);
  CHECK(r.signal == 0);  // it handles the signal: exits, does not die
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("interrupted") != std::string::npos);
  CHECK(listing(city) == before);
  CHECK(noLeftovers(city));
  fs::remove_all(city.parent_path());
}
