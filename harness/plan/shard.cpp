#include "harness/plan/shard.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <sstream>
#include <unordered_map>

#include "harness/core/input_error.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/plan/cell_record.hpp"
#include "harness/plan/merge.hpp"
#include "harness/plan/worker.hpp"

namespace dropcheck {
namespace {

std::size_t whole(const std::string& text, const std::string& all) {
  std::size_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw InputError("", 0, "--shard",
                     "expected I/N (whole numbers, 1 <= I <= N), got " + excerpt(all));
  return v;
}

std::string padded(std::size_t v, std::size_t width) {
  std::string s = std::to_string(v);
  return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

}  // namespace

ShardSpec parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos)
    throw InputError("", 0, "--shard", "expected I/N, got " + excerpt(text));
  const std::size_t i = whole(text.substr(0, slash), text), n = whole(text.substr(slash + 1), text);
  if (n < 1 || n > kMaxShards || i < 1 || i > n)
    throw InputError("", 0, "--shard",
                     "expected 1 <= I <= N <= " + std::to_string(kMaxShards) + ", got " + text);
  return {i - 1, n};
}

std::string shard_file_name(ShardSpec s) {
  const std::size_t width = std::to_string(s.count).size();
  return "shard-" + padded(s.index + 1, width) + "-of-" + padded(s.count, width) + ".jsonl";
}

std::vector<std::size_t> cells_of_shard(const Plan& plan, ShardSpec s) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < plan.cell_count(); ++i)
    if (shard_of(plan.cell(i).key, s.count) == s.index) out.push_back(i);
  return out;
}

std::vector<std::size_t> cells_from(const Plan& plan, const std::string& path,
                                    std::string& file_name) {
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < plan.cell_count(); ++i) index.emplace(plan.cell(i).key, i);
  LineReader in(path, kMaxPlanBytes, kMaxRecordLine, "a list of cells");
  std::vector<std::size_t> out;
  for (std::string key; in.next(key);) {
    if (key.empty()) continue;
    const auto it = index.find(key);
    if (it == index.end())
      throw InputError(in.name(), static_cast<int>(in.line_number()), "",
                       "cell " + excerpt(key) + " is not in plan " + plan.hash);
    out.push_back(it->second);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw InputError(path, 0, "", "lists no cell");
  std::string joined;
  for (std::size_t i : out) joined += plan.cell(i).key + "\n";
  file_name = "cells-" + fnv1a_hex(joined) + ".jsonl";
  return out;
}

namespace {

// The cached record of `c`, or an empty one; a cache entry that cannot be read is no entry.
CellRecord cached(const Plan& plan, const Cell& c, const std::string& entry) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(entry, ec))) return {};
  try {
    return adopt_record(plan, c,
                        read_regular_file(entry, kMaxPlanBytes, "a cache entry", Links::refuse));
  } catch (const InputError&) {
    return {};
  }
}

std::string cache_entry(const std::string& cache, const Plan& plan, const Cell& c) {
  const std::string id = cell_identity(plan, c);
  return (std::filesystem::path(cache) / id.substr(0, 2) / (id + ".json")).string();
}

// Keeps a record in the cache. A link planted in the cache while the sweep ran is never written
// through: the record is then kept in the shard file alone, and the progress says so.
void cache_record(const std::string& cache, const std::string& entry, const std::string& line,
                  std::ostream& progress) {
  try {
    check_no_links_below(cache, entry, "--cache");
    write_file_atomic(entry, line + "\n", Links::refuse);
  } catch (const InputError& e) {
    progress << "not cached: " << e.what() << "\n";
  }
}

}  // namespace

ShardSummary run_cells(const Plan& plan, const std::vector<std::size_t>& cells,
                       const std::string& out, std::ostream& progress, const std::string& cache,
                       int jobs) {
  ShardSummary s;
  std::vector<std::string> keys, entries(cells.size());
  std::vector<CellRecord> got(cells.size());
  std::vector<std::size_t> todo_at, todo;  // positions in `cells` to run, and their cells
  const auto report = [&](std::size_t at) {
    const CellRecord& r = got[at];
    ++s.cells;
    (r.status == "ok" ? s.ok : r.status == "skipped" ? s.skipped : s.failed) += 1;
    progress << "cell " << s.cells << " of " << cells.size() << ": " << keys[at] << ": " << r.status
             << "\n";
  };
  // Each cell's cache entry, and a link at any depth of the cache refused before any is read.
  if (!cache.empty())
    for (std::size_t at = 0; at < cells.size(); ++at) {
      entries[at] = cache_entry(cache, plan, plan.cell(cells[at]));
      check_no_links_below(cache, entries[at], "--cache");
    }
  for (std::size_t at = 0; at < cells.size(); ++at) {
    const Cell c = plan.cell(cells[at]);
    keys.push_back(c.key);
    if (!cache.empty()) got[at] = cached(plan, c, entries[at]);
    if (got[at].line.empty()) {
      todo_at.push_back(at);
      todo.push_back(cells[at]);
      continue;
    }
    ++s.cached;
    report(at);
  }
  run_cells_in_worker(
      plan, todo,
      [&](std::size_t k, const CellRecord& r) {
        const std::size_t at = todo_at[k];
        got[at] = r;
        if (!entries[at].empty()) cache_record(cache, entries[at], r.line, progress);
        report(at);
      },
      kWorkerSilenceLimit, nullptr, jobs);
  std::vector<std::pair<std::string, std::string>> records;  // key, record
  for (std::size_t at = 0; at < cells.size(); ++at)
    records.emplace_back(std::move(keys[at]), std::move(got[at].line));
  std::sort(records.begin(), records.end());
  write_file_atomic(
      out,
      [&](std::ostream& o) {
        for (const auto& [key, record] : records) o << record << "\n";
      },
      Links::refuse);
  return s;
}

}  // namespace dropcheck
