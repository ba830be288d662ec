// What a command reads and writes, checked before any engine runs: every output is a place the
// user named, writable, not one of the inputs, and not shared with another output.
#pragma once

#include <string>
#include <vector>

#include "harness/io/link_policy.hpp"

namespace dropcheck {

class OutputPlan {
 public:
  // An input file or folder (a scene, a result set): no output may land on it or inside it.
  void read(const std::string& path);
  // An output file named by option `key` ("--csv"): replaced atomically when the run succeeds.
  void write_file(const std::string& key, const std::string& path);
  // An output folder named by `key` ("--out") that the command replaces whole (the report).
  void write_folder(const std::string& key, const std::string& path);
  // A folder named by `key` that the command writes files into (bless --out): created if absent.
  void write_into(const std::string& key, const std::string& path);
  // A file the command writes inside such a folder: like write_file, but a symbolic link there is
  // refused, never written through (the folder may come from someone else).
  void write_entry(const std::string& key, const std::string& path);
  // An entry at depth below `root`, a folder the command fills (a cache): no folder between `root`
  // and the entry may be a link either (check_no_links_below).
  void write_entry_below(const std::string& key, const std::string& root, const std::string& path);

  // Throws InputError naming the option and the problem: an empty path, a path that names a
  // folder where a file is expected, something that is not a regular file, a place that cannot be
  // written (under a regular file, /proc, no permission), an output that is an input or lies inside
  // an input folder, an input inside a replaced folder, or two outputs on one path.
  void check() const;

 private:
  struct Output {
    std::string key, path;
    enum class Kind { file, entry, folder, into } kind;
    std::string root;  // an entry's folder that no link may lie below (empty: none)
    bool is_file() const { return kind == Kind::file || kind == Kind::entry; }
    Links links() const { return kind == Kind::entry ? Links::refuse : Links::follow; }
  };
  std::vector<std::string> inputs_;
  std::vector<Output> outputs_;
};

}  // namespace dropcheck
