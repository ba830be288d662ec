#include "harness/plan/merge.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_set>

#include "harness/core/input_error.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/json_text.hpp"
#include "harness/plan/cell_record.hpp"

namespace dropcheck {
namespace {

namespace fs = std::filesystem;

bool is_shard_name(const std::string& name) {
  const bool ends = name.size() > 6 && name.compare(name.size() - 6, 6, ".jsonl") == 0;
  return ends && (name.rfind("shard-", 0) == 0 || name.rfind("cells-", 0) == 0);
}

// The shard files of `dir`, by name. A matching entry that is not a regular file is refused: the
// folder is filled by many jobs, and a link there could lead the read out of it.
std::vector<fs::path> shard_files(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("", 0, "DIR", excerpt(dir) + " is not a folder of shard files");
  std::vector<fs::path> out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!is_shard_name(name)) continue;
    if (!fs::is_regular_file(e.symlink_status(ec)))
      throw InputError(escape_controls(e.path().string()), 0, "",
                       "not a regular file (a link or a folder): shard files are read only as "
                       "files of the folder itself");
    out.push_back(e.path());
  }
  if (ec) throw InputError(dir, 0, "", "cannot list: " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::unordered_set<std::string> cell_keys(const Plan& plan) {
  std::unordered_set<std::string> keys;
  for (std::size_t i = 0; i < plan.cell_count(); ++i) keys.insert(plan.cell(i).key);
  return keys;
}

std::string record_key(const Plan& plan, const std::unordered_set<std::string>& keys,
                       const std::string& file, long long line, const std::string& text) {
  nlohmann::json j;
  try {
    j = parse_json<nlohmann::json>(text);
  } catch (const std::exception&) {
    throw InputError(file + ":" + std::to_string(line), 0, "",
                     "not a JSON record: " + excerpt(text));
  }
  if (!j.is_object() || !j.contains("format") || j["format"] != kRecordFormat ||
      !j.contains("key") || !j["key"].is_string() || !j.contains("plan"))
    throw InputError(file + ":" + std::to_string(line), 0, "",
                     "not a " + std::string(kRecordFormat) + " record");
  if (j["plan"] != plan.hash)
    throw InputError(
        file, line, "plan",
        "this record belongs to plan " +
            (j["plan"].is_string() ? excerpt(j["plan"].get<std::string>())
                                   : std::string("of a JSON ") + j["plan"].type_name()) +
            ", not " + plan.hash);
  std::string key = j["key"].get<std::string>();
  if (!keys.count(key))
    throw InputError(file + ":" + std::to_string(line), 0, "key",
                     "cell " + excerpt(key) + " is not in the plan");
  return key;
}

MergeResult merge_shards(const Plan& plan, const std::string& dir, const std::string& out) {
  const std::unordered_set<std::string> keys = cell_keys(plan);
  struct Seen {
    std::string line, file;
  };
  std::map<std::string, Seen> records;
  MergeResult m;
  for (const fs::path& path : shard_files(dir)) {
    // Read a line at a time; names in messages escaped (a planted file name could carry controls).
    LineReader in(path.string(), kMaxShardBytes, kMaxRecordLine, "a shard file", Links::refuse);
    const std::string& file = in.name();
    ++m.files;
    for (std::string line; in.next(line);) {
      const long long n = in.line_number();
      if (line.empty()) continue;
      const std::string key = record_key(plan, keys, file, n, line);
      const auto [it, added] = records.try_emplace(key, Seen{line, file});
      if (!added && it->second.line != line)
        throw InputError(file + ":" + std::to_string(n), 0, "",
                         "cell " + excerpt(key) + " is also in " + it->second.file +
                             " with different bytes (a different build or library? rerun one)");
    }
  }
  m.records = records.size();
  for (std::size_t i = 0; i < plan.cell_count(); ++i) {
    std::string key = plan.cell(i).key;
    if (!records.count(key)) m.missing.push_back(std::move(key));
  }
  if (!m.missing.empty()) return m;
  write_file_atomic(out, [&](std::ostream& o) {
    for (const auto& [key, seen] : records) o << seen.line << "\n";
  });
  return m;
}

}  // namespace dropcheck
