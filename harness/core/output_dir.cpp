#include "harness/core/output_dir.hpp"

#include <unistd.h>

#include <filesystem>

#include "harness/core/input_error.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

bool report_file(const fs::directory_entry& e) {
  const std::string name = e.path().filename().string();
  return e.is_regular_file() && (name == "README.md" || e.path().extension() == ".svg");
}

// "reports/" -> "reports": the directory itself, without a trailing separator.
fs::path normal(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  return p.filename().empty() && p.has_parent_path() ? p.parent_path() : p;
}

// A sibling of `target` named ".<name>.<what>-<pid>".
fs::path sibling(const fs::path& target, const std::string& what) {
  return target.parent_path() /
         ("." + target.filename().string() + "." + what + "-" + std::to_string(::getpid()));
}

}  // namespace

void check_replaceable(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec))
    throw InputError(dir, 0, "--out", "exists and is not a directory");
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (!report_file(e))
      throw InputError(dir, 0, "--out",
                       "holds '" + e.path().filename().string() +
                           "', which dropcheck report did not write; refusing to replace it");
  if (ec) throw InputError(dir, 0, "--out", "cannot list: " + ec.message());
}

StagingDir::StagingDir(const std::string& target) : target_(normal(target).string()) {
  const fs::path p = sibling(target_, "staging");
  std::error_code ec;
  fs::remove_all(p, ec);
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
  if (!fs::create_directory(p, ec) || ec)
    throw InputError(p.string(), 0, "", "cannot create the staging directory: " + ec.message());
  path_ = p.string();
}

StagingDir::~StagingDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void StagingDir::commit() {
  const fs::path target(target_), backup = sibling(target, "previous");
  std::error_code ec;
  fs::remove_all(backup, ec);
  const bool had_target = fs::exists(target, ec);
  if (had_target) {
    fs::rename(target, backup, ec);
    if (ec)
      throw InputError(target_, 0, "", "cannot move the previous output aside: " + ec.message());
  }
  fs::rename(path_, target, ec);
  if (ec) {
    std::error_code ignored;
    if (had_target) fs::rename(backup, target, ignored);
    throw InputError(target_, 0, "", "cannot move the new output into place: " + ec.message());
  }
  committed_ = true;
  if (had_target) fs::remove_all(backup, ec);
}

}  // namespace dropcheck
