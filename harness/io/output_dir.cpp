#include "harness/io/output_dir.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2
#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "harness/core/input_error.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/process/signal_cleanup.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

constexpr const char* kManifestHeader =
    "# files written by dropcheck report; it replaces only these";
constexpr const char* kReportTitle = "# dropcheck comparison report";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// "reports/" -> "reports", then a symbolic link followed to the folder it names.
fs::path resolved(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.filename().empty() && p.has_parent_path()) p = p.parent_path();
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(p, ec); ++hops) {
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) break;
    p = (link.is_absolute() ? link : p.parent_path() / link).lexically_normal();
  }
  return p;
}

// The names a manifest lists (empty set when there is no manifest).
std::set<std::string> manifest_names(const fs::path& dir, bool& present) {
  std::set<std::string> names;
  std::error_code ec;
  present = fs::is_regular_file(dir / kManifestName, ec);
  if (!present) return names;
  std::istringstream lines(read_text(dir / kManifestName));
  std::string line;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] != '#') names.insert(line);
  return names;
}

// Why `e` is not one dropcheck wrote ("" when it is).
std::string foreign(const fs::directory_entry& e, bool has_manifest,
                    const std::set<std::string>& listed, const std::string& readme) {
  const std::string name = e.path().filename().string();
  std::error_code ec;
  if (name == kManifestName) return {};
  if (e.is_symlink(ec) || !e.is_regular_file(ec))
    return "holds '" + name + "', which is not a regular file";
  if (has_manifest)
    return listed.count(name)
               ? ""
               : "holds '" + name + "', which its " + kManifestName + " does not list";
  if (name == "README.md")
    return readme.rfind(kReportTitle, 0) == 0 ? ""
                                              : "holds a README.md that is not a dropcheck report";
  if (e.path().extension() == ".svg" && readme.find("(" + name + ")") != std::string::npos)
    return {};
  return "holds '" + name + "', which dropcheck report did not write";
}

// Creates a unique folder ".<name>.<what>-XXXXXX" beside `target`.
std::string unique_sibling(const fs::path& target, const std::string& what) {
  std::string tmpl = (target.parent_path() /
                      ("." + target.filename().string().substr(0, 180) + "." + what + "-XXXXXX"))
                         .string();
  if (!::mkdtemp(tmpl.data()))
    throw InputError(target.string(), 0, "--out",
                     "cannot create the " + what + " folder beside it: " + std::strerror(errno));
  return tmpl;
}

void write_manifest(const fs::path& staging) {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(staging))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string text = std::string(kManifestHeader) + "\n";
  for (const std::string& n : names) text += n + "\n";
  write_file_atomic((staging / kManifestName).string(), text);
}

// The old way, for a file system without RENAME_EXCHANGE: target -> backup, staging -> target.
void swap_by_backup(const fs::path& staging, const fs::path& target) {
  const SignalsDeferred deferred;  // a kill mid-swap would leave the old output aside
  const fs::path backup = unique_sibling(target, "previous");
  std::error_code ec;
  fs::rename(target, backup, ec);  // onto the empty backup folder
  if (ec) {
    fs::remove(backup, ec);
    throw InputError(target.string(), 0, "",
                     "cannot move the previous output aside: " + ec.message());
  }
  fs::rename(staging, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::rename(backup, target, ignored);
    throw InputError(target.string(), 0, "",
                     "cannot move the new output into place: " + ec.message());
  }
  fs::remove_all(backup, ec);
}

}  // namespace

void check_replaceable(const std::string& dir) {
  const fs::path p = resolved(dir);
  std::error_code ec;
  if (!fs::exists(p, ec)) return;
  if (!fs::is_directory(p, ec)) throw InputError(dir, 0, "--out", "exists and is not a directory");
  bool has_manifest = false;
  const std::set<std::string> listed = manifest_names(p, has_manifest);
  const std::string readme = has_manifest ? "" : read_text(p / "README.md");
  for (const fs::directory_entry& e : fs::directory_iterator(p, ec))
    if (const std::string why = foreign(e, has_manifest, listed, readme); !why.empty())
      throw InputError(dir, 0, "--out",
                       why + "; refusing to replace a folder dropcheck did not write");
  if (ec) throw InputError(dir, 0, "--out", "cannot list: " + ec.message());
}

StagingDir::StagingDir(const std::string& target) : target_(resolved(target).string()) {
  const fs::path t(target_);
  std::error_code ec;
  if (t.has_parent_path()) fs::create_directories(t.parent_path(), ec);
  const SignalsDeferred deferred;  // create + register as one step
  path_ = unique_sibling(t, "staging");
  cleanup_ = std::make_unique<CleanupOnSignal>(path_, true);
}

StagingDir::~StagingDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
}

namespace {

// The mode the report folder gets: the replaced folder's own, or what mkdir gives a new folder
// (0777 less the umask). mkdtemp made the staging folder 0700, private while it is built.
mode_t folder_mode(const std::string& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return st.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0777 & ~mask;
}

}  // namespace

void StagingDir::commit() {
  write_manifest(path_);
  if (::chmod(path_.c_str(), folder_mode(target_)) != 0)
    throw InputError(target_, 0, "",
                     std::string("cannot set the folder's mode: ") + std::strerror(errno));
  for (int attempt = 0; attempt < 3 && !committed_; ++attempt) {
    check_replaceable(target_);  // again: another run or a person may have written there meanwhile
    if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
      committed_ = true;  // path_ now holds the previous output
      std::error_code ec;
      fs::remove_all(path_, ec);
    } else if (errno == ENOENT) {
      if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, target_.c_str(), RENAME_NOREPLACE) == 0)
        committed_ = true;
      else if (errno != EEXIST)  // EEXIST: another run created it meanwhile; exchange with it
        throw InputError(
            target_, 0, "",
            std::string("cannot move the new output into place: ") + std::strerror(errno));
    } else if (errno == EINVAL || errno == ENOSYS) {
      swap_by_backup(path_, target_);
      committed_ = true;
    } else {
      throw InputError(
          target_, 0, "",
          std::string("cannot swap the new output into place: ") + std::strerror(errno));
    }
  }
  if (!committed_)
    throw InputError(target_, 0, "", "cannot move the new output into place: it keeps changing");
  cleanup_->release();
}

}  // namespace dropcheck
