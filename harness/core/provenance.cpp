#include "harness/core/provenance.hpp"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "harness/core/build_id.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Everything `command` prints on stdout (stderr discarded), trailing newlines removed; "" on error.
std::string output_of(const std::string& command) {
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return {};
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  if (pclose(pipe) != 0) return {};
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string or_unknown(const std::string& s) {
  return s.empty() ? "unknown" : s;
}

// `output_dir` relative to the checkout's top level ("reports"), or "" when it lies outside.
std::string relative_to_top(const std::string& git, const std::string& output_dir) {
  const std::string top = output_of(git + " rev-parse --show-toplevel");
  if (top.empty() || output_dir.empty()) return {};
  std::error_code ec;
  const fs::path rel = fs::relative(fs::absolute(output_dir, ec), top, ec).lexically_normal();
  const std::string text = rel.generic_string();
  return ec || text.empty() || text == "." || text.rfind("..", 0) == 0 ? "" : text;
}

// Whether a `git status --porcelain` line ("XY path") names a path under `dir` (relative to top).
bool under(const std::string& line, const std::string& dir) {
  if (dir.empty() || line.size() < 4) return false;
  const std::string path = line.substr(3);
  return path == dir || path.rfind(dir + "/", 0) == 0;
}

std::string commit_of(const std::string& git, const std::string& output_dir) {
  const std::string hash = output_of(git + " rev-parse --short HEAD");
  if (hash.empty()) return {};
  // Tracked files only: untracked files do not change what HEAD's sources build.
  const std::string ignore = relative_to_top(git, output_dir);
  std::istringstream changes(output_of(git + " status --porcelain --untracked-files=no"));
  for (std::string line; std::getline(changes, line);)
    if (!under(line, ignore)) return hash + "-dirty";
  return hash;
}

}  // namespace

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    std::string model = line.substr(colon + 1);
    model.erase(0, model.find_first_not_of(" \t"));
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical CPUs";
  }
  return {};
}

std::string iso_date_from_epoch(const std::string& epoch) {
  if (epoch.empty() || epoch.size() > 15 ||
      epoch.find_first_not_of("0123456789") != std::string::npos)
    return {};
  const std::time_t t = static_cast<std::time_t>(std::atoll(epoch.c_str()));
  std::tm utc{};
  if (!gmtime_r(&t, &utc)) return {};
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

Provenance current_provenance(const std::string& dir, const std::string& output_dir) {
  // Outside a checkout (a report written from elsewhere): the tree this binary was built from.
  std::string git = "git -C " + shell_quoted(dir);
  if (output_of(git + " rev-parse --show-toplevel").empty())
    git = "git -C " + shell_quoted(source_tree());
  Provenance p;
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  p.date = epoch ? iso_date_from_epoch(epoch) : "";
  if (p.date.empty()) p.date = output_of(git + " log -1 --format=%cI");
  p.date = or_unknown(p.date);
  p.commit = or_unknown(commit_of(git, output_dir));
  const BuildId build = current_build();
  p.build = build.key;
  p.build_type = or_unknown(build.build_type);
  p.flags = build.flags.empty() ? "(none)" : build.flags;
  p.cpu = or_unknown(cpu_model());
  return p;
}

}  // namespace dropcheck
