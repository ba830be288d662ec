#include "harness/io/output_plan.hpp"

#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "harness/core/input_error.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_dir.hpp"
#include "harness/process/signal_cleanup.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

// An absolute path with every symbolic link of its existing part resolved (the rest as written).
fs::path canonical_path(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  if (ec) c = fs::absolute(p, ec).lexically_normal();
  if (c.filename().empty() && c.has_parent_path()) c = c.parent_path();
  return c;
}

// True when `inner` is `outer` or lies inside it (paths canonical).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);  // hard links too
  return canonical_path(a) == canonical_path(b);
}

// The closest folder that exists at or above `p` ("." for a relative path with none).
fs::path existing_ancestor(const fs::path& p, const std::string& key, const std::string& shown) {
  fs::path a = p;
  std::error_code ec;
  while (!a.empty() && !fs::exists(a, ec)) a = a.parent_path();
  if (a.empty()) a = ".";
  if (!fs::is_directory(a, ec))
    throw InputError(shown, 0, key,
                     "cannot be created: '" + a.string() + "' is a file, not a folder");
  return a;
}

// Creates and removes a scratch file in `dir`: the only sure test that dropcheck may write there
// (access() says yes to root, even on /proc or a read-only mount).
void probe_writable(const fs::path& dir, const std::string& key, const std::string& shown) {
  std::string probe = (dir / ".dropcheck-probe-XXXXXX").string();
  const SignalsDeferred deferred;  // a kill between mkstemp and unlink must not leave the probe
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw InputError(shown, 0, key,
                     "cannot write in '" + dir.string() + "': " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

void check_not_empty(const std::string& key, const std::string& path) {
  if (path.empty()) throw InputError("", 0, key, "expects a path, got an empty string");
  if (path.find('\0') != std::string::npos)
    throw InputError("", 0, key, "the path holds a NUL byte");
}

void check_file(const std::string& key, const std::string& path, Links links) {
  const fs::path p(path);
  const std::string last = p.filename().string();
  if (last.empty() || last == "." || last == "..")
    throw InputError(path, 0, key, "names a folder; expected a file name");
  const fs::path target = output_target(path, key, links);  // refuses folders, devices, FIFOs
  probe_writable(existing_ancestor(target.parent_path(), key, path), key, path);
}

void check_folder(const std::string& key, const std::string& path, bool replaced) {
  const fs::path c = canonical_path(path);
  std::error_code ec;
  if (fs::exists(c, ec) && !fs::is_directory(c, ec))
    throw InputError(path, 0, key, "exists and is not a folder");
  if (replaced) {
    if (!c.has_relative_path()) throw InputError(path, 0, key, "is the root folder");
    if (within(canonical_path(fs::current_path(ec)), c))
      throw InputError(path, 0, key, "is the current folder or holds it; name a folder of its own");
    check_replaceable(path);
    probe_writable(existing_ancestor(c.parent_path(), key, path), key, path);
  } else {
    probe_writable(existing_ancestor(c, key, path), key, path);
  }
}

}  // namespace

void OutputPlan::read(const std::string& path) {
  inputs_.push_back(path);
}

void OutputPlan::write_file(const std::string& key, const std::string& path) {
  outputs_.push_back({key, path, Output::Kind::file, ""});
}

void OutputPlan::write_entry(const std::string& key, const std::string& path) {
  outputs_.push_back({key, path, Output::Kind::entry, ""});
}

void OutputPlan::write_entry_below(const std::string& key, const std::string& root,
                                   const std::string& path) {
  outputs_.push_back({key, path, Output::Kind::entry, root});
}

void OutputPlan::write_folder(const std::string& key, const std::string& path) {
  outputs_.push_back({key, path, Output::Kind::folder, ""});
}

void OutputPlan::write_into(const std::string& key, const std::string& path) {
  outputs_.push_back({key, path, Output::Kind::into, ""});
}

void OutputPlan::check() const {
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    const Output& o = outputs_[i];
    check_not_empty(o.key, o.path);
    if (!o.root.empty()) check_no_links_below(o.root, o.path, o.key);
    if (o.is_file())
      check_file(o.key, o.path, o.links());
    else
      check_folder(o.key, o.path, o.kind == Output::Kind::folder);
    const fs::path target =
        o.is_file() ? output_target(o.path, o.key, o.links()) : fs::path(o.path);
    const fs::path out = canonical_path(target);
    for (const std::string& in : inputs_) {
      const fs::path c = canonical_path(in);
      if (o.is_file() && (same_file(target, in) || within(out, c)))
        throw InputError(
            o.path, 0, o.key,
            "is an input ('" + in + "') or lies inside one; refusing to write over it");
      if (o.kind == Output::Kind::folder && within(c, out))
        throw InputError(o.path, 0, o.key, "holds the input '" + in + "', and would be replaced");
    }
    for (std::size_t j = 0; j < i; ++j)
      if (outputs_[j].is_file() && o.is_file() &&
          same_file(output_target(outputs_[j].path, "", outputs_[j].links()), target))
        throw InputError(o.path, 0, o.key,
                         "is also the path of " + outputs_[j].key + "; name two different files");
  }
}

}  // namespace dropcheck
