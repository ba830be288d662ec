#include "harness/guard/bless.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "harness/core/input_error.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/baseline_parse.hpp"
#include "harness/guard/regression.hpp"
#include "harness/guard/regression_physics.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/file_slug.hpp"

namespace dropcheck {
namespace {

// The file's text, or "" when there is none. Only a regular file is read, never through a link:
// the folder may come from someone else (output_plan.hpp, write_entry).
std::string read_or_empty(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::symlink_status(path, ec).type() == std::filesystem::file_type::not_found)
    return {};
  return read_regular_file(path, kMaxBaselineBytes, "512 MiB, for a baseline", Links::refuse);
}

// The file `old` (read from `path`), which holds the same numbers as this build's run `b`: `b`
// under the file's provenance and build keys, this build's added (the oldest other dropped when it
// holds kMaxBuildKeys); "" when the file names this build already.
std::string with_this_build(const std::string& old, const std::string& path, const Baseline& b) {
  const Baseline kept = parse_baseline(old, path);
  const std::string& key = b.build_keys.front();
  std::vector<std::string> keys = kept.build_keys;
  if (std::find(keys.begin(), keys.end(), key) != keys.end()) return {};
  if (keys.size() >= kMaxBuildKeys) keys.erase(keys.begin());
  keys.push_back(key);
  Baseline out = b;
  out.provenance = kept.provenance;
  out.build_keys = keys;
  return baseline_to_text(out);
}

// Writes one baseline unless the file already holds the same data; returns the log line. A file
// with the same numbers made by another build gains this build's key, so that the bits tier runs
// on both (a compiler that gives the same bits); new numbers replace the file and its keys.
std::string write_one(const Baseline& b, const std::string& dir) {
  const std::string path = baseline_path(dir, b.scene, b.engine);
  const std::string text = baseline_to_text(b), old = read_or_empty(path);
  std::string what = b.skipped.empty() ? "hash " + b.hash : "skipped: " + b.skipped;
  if (!b.failed_tiers.empty()) what += "; FAILED " + b.failed_tiers;
  if (!old.empty() && same_data(old, text)) {
    const std::string added = with_this_build(old, path, b);
    if (added.empty()) return "unchanged " + path + " (" + what + ")";
    write_file_atomic(path, added, Links::refuse);
    return "same data " + path + " (" + what + "; build key added: " + b.build_keys.front() + ")";
  }
  write_file_atomic(path, text, Links::refuse);
  return (old.empty() ? "new       " : "updated   ") + path + " (" + what + ")";
}

}  // namespace

std::string baseline_path(const std::string& dir, const std::string& scene,
                          const std::string& engine) {
  return (std::filesystem::path(dir) / baseline_file_name(file_slug(scene), file_slug(engine)))
      .string();
}

std::vector<std::string> baseline_paths(const std::vector<Scene>& scenes,
                                        const std::vector<std::string>& engines,
                                        const std::string& dir) {
  std::vector<std::string> out;
  std::map<std::string, std::string> owner;  // path -> the scene (and its file) that claimed it
  for (const Scene& scene : scenes) {
    for (const std::string& engine : engines) {
      const std::string path = baseline_path(dir, scene.name, engine);
      const std::string who = "scene \"" + scene.name + "\" (" + scene.source + ")";
      auto [it, fresh] = owner.emplace(path, who);
      if (!fresh)
        throw InputError(
            path, 0, "name",
            it->second + " and " + who + " would both be written here; give them distinct names");
      out.push_back(path);
    }
  }
  return out;
}

bool is_golden_set(const std::string& dir) {
  std::error_code ec;
  const auto a = std::filesystem::weakly_canonical(dir, ec);
  const auto b = std::filesystem::weakly_canonical("tests/baselines", ec);
  return !ec && a == b;
}

BlessOutcome bless(const std::vector<Scene>& scenes, const std::vector<NamedFactory>& engines,
                   const BlessOptions& options) {
  BlessOutcome out;
  std::vector<std::string> engine_names;
  for (const NamedFactory& e : engines) engine_names.push_back(e.first);
  baseline_paths(scenes, engine_names, options.out_dir);  // refuses colliding names before any run
  std::vector<Baseline> made;
  for (const Scene& scene : scenes) {
    for (const NamedFactory& engine : engines) {
      Baseline b = make_baseline(scene, engine.second, options.baseline);
      b.provenance = provenance(options.commit);
      const std::string before = baseline_path(options.baselines_dir, scene.name, engine.first);
      const std::optional<Baseline> baseline = read_baseline_if_present(before);
      const TierResult physics =
          check_physics(b, baseline ? &*baseline : nullptr,
                        core_checks(scene, engine.second, options.reference), scene.world.contacts);
      if (physics.verdict == TierVerdict::failed) {
        out.refused.push_back(physics.message);
        b.failed_tiers = "physics: " + physics.message;
      }
      made.push_back(std::move(b));
    }
  }
  if (!out.refused.empty() && (options.refuse_failed || is_golden_set(options.out_dir))) return out;
  out.failed = std::move(out.refused);  // written, and marked in the files
  out.refused.clear();
  for (const Baseline& b : made) out.lines.push_back(write_one(b, options.out_dir));
  return out;
}

}  // namespace dropcheck
