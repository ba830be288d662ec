// The cost of the sweep path, printed as figures (docs/sweeps.md, "Cost"):
//  1. cells per second of `dropcheck sweep` (run_cells: one worker process for the shard, a cell
//     it dies in rerun alone, records sorted and written whole) against the same cells run in one
//     loop in this process (no isolation, no file), on sweeps/small.toml's 256 cells;
//  2. the same 256 cells on 1, 2 and every usable core's worth of workers (`sweep --jobs`),
//     pulling from one queue: cells per second and the speed-up over one worker;
//  3. a plan of 10^5 cells: planned, its records (synthetic: right format, key and plan, 600 bytes
//     each, no runs) split into 1000 shard files by their keys, then merged: the merge's wall time
//     and the process's peak resident memory.
//   dropcheck_sweep_scale [SOURCE_DIR]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "harness/core/registry.hpp"
#include "harness/plan/cell_record.hpp"
#include "harness/plan/merge.hpp"
#include "harness/plan/shard.hpp"
#include "harness/plan/worker.hpp"
#include "harness/run/isolated_run.hpp"

namespace fs = std::filesystem;
using namespace dropcheck;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double peak_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

void sweep_against_loop(const std::string& source, const fs::path& tmp) {
  const Plan plan = make_plan(load_sweep(source + "/sweeps/small.toml", known_engine_names()));
  std::vector<std::size_t> all(plan.cell_count());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::ostringstream quiet;
  for (int round = 0; round < 5; ++round) {
    auto t = Clock::now();
    for (std::size_t i : all) (void)run_cell(plan, plan.cell(i), Isolation::in_process);
    const double loop = seconds_since(t);
    t = Clock::now();
    run_cells(plan, all, (tmp / "shard.jsonl").string(), quiet);
    const double sweep = seconds_since(t);
    const double n = static_cast<double>(all.size());
    std::printf(
        "round %d: %zu cells: one loop %.3f s (%.0f cells/s), sweep path %.3f s (%.0f "
        "cells/s): %.0f %%\n",
        round + 1, all.size(), loop, n / loop, sweep, n / sweep, 100.0 * loop / sweep);
  }
}

void sweep_on_cores(const std::string& source, const fs::path& tmp) {
  const Plan plan = make_plan(load_sweep(source + "/sweeps/small.toml", known_engine_names()));
  std::vector<std::size_t> all(plan.cell_count());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::vector<int> jobs{1, 2};
  if (usable_cores() > 2) jobs.push_back(usable_cores());
  std::ostringstream quiet;
  for (int round = 0; round < 3; ++round) {
    double one = 0.0;
    for (int j : jobs) {
      const auto t = Clock::now();
      run_cells(plan, all, (tmp / "jobs.jsonl").string(), quiet, "", j);
      const double s = seconds_since(t);
      if (j == 1) one = s;
      std::printf("round %d: %zu cells on %d worker%s: %.3f s (%.0f cells/s), %.2f x one\n",
                  round + 1, all.size(), j, j == 1 ? "" : "s", s,
                  static_cast<double>(all.size()) / s, one / s);
    }
  }
}

void merge_at_scale(const std::string& source, const fs::path& tmp) {
  std::ofstream(tmp / "big.toml")
      << "scenes = [\"" << source << "/scenarios/extreme/stiff_spring.toml\"]\n"
      << "engines = [\"ours\"]\n"
      << "[[axis]]\nkey = \"world.gravity[0]\"\nfrom = 0.0\nto = 1.0\ncount = 100\n"
      << "[[axis]]\nkey = \"world.gravity[2]\"\nfrom = 0.0\nto = 1.0\ncount = 1000\n";
  auto t = Clock::now();
  const Plan plan = make_plan(load_sweep((tmp / "big.toml").string(), known_engine_names()));
  const double planned = seconds_since(t);
  const std::size_t shards = 1000;
  t = Clock::now();
  std::map<std::size_t, std::string> files;
  const std::string padding(480, 'x');
  for (std::size_t i = 0; i < plan.cell_count(); ++i) {
    const Cell c = plan.cell(i);
    files[shard_of(c.key, shards)] += "{\"format\":\"dropcheck-record/1\",\"key\":\"" + c.key +
                                      "\",\"plan\":\"" + plan.hash + "\",\"padding\":\"" + padding +
                                      "\"}\n";
  }
  fs::create_directories(tmp / "shards");
  for (const auto& [s, text] : files)
    std::ofstream(tmp / "shards" / shard_file_name({s, shards})) << text;
  const double split = seconds_since(t);
  files.clear();
  const double before = peak_mib();
  t = Clock::now();
  const MergeResult m = merge_shards(plan, (tmp / "shards").string(), (tmp / "all.jsonl").string());
  const double merged = seconds_since(t);
  std::printf(
      "plan of %zu cells: planned in %.2f s; records split into %zu shard files in %.2f s; "
      "merged (%zu records, %zu missing, %.0f MiB) in %.2f s; peak resident memory %.0f "
      "MiB (%.0f MiB before the merge)\n",
      plan.cell_count(), planned, m.files, split, m.records, m.missing.size(),
      static_cast<double>(fs::file_size(tmp / "all.jsonl")) / 1048576.0, merged, peak_mib(),
      before);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string source = argc > 1 ? argv[1] : DROPCHECK_SOURCE_DIR;
  const fs::path tmp =
      fs::temp_directory_path() / ("dropcheck-sweep-scale-" + std::to_string(getpid()));
  fs::create_directories(tmp);
  sweep_against_loop(source, tmp);
  sweep_on_cores(source, tmp);
  merge_at_scale(source, tmp);
  fs::remove_all(tmp);
  return 0;
}
