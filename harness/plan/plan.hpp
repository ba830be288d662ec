// A plan: a sweep file resolved into everything its cells need, so that any machine can run any
// share of it (docs/sweeps.md). The scenes' texts are inside the plan; the cells are the product of
// scenes x engines x each axis's values, in that order, each named by a key
//   "free_fall_drag|ours|timestep=1/60|damping_rate=0.5"
// and assigned to one of N shards by a hash of that key alone (shard_of), so that adding cells to a
// sweep never moves the others. The plan's hash covers all of it: a record names the plan it
// belongs to, and a shard of another plan is refused at merge.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/plan/sweep_file.hpp"

namespace dropcheck {

struct PlanScene {
  std::string name;  // the scene's name (unique within a plan)
  std::string file;  // where it was read, for messages
  std::string text;  // the scene file's bytes
};

struct Cell {
  std::size_t scene = 0, engine = 0;
  std::vector<std::size_t> values;  // an index into each axis's values
  std::string key;
};

struct Plan {
  std::string sweep;  // the sweep file it was planned from
  std::string description;
  std::vector<PlanScene> scenes;
  std::vector<std::string> engines;      // registry names and external engines' ids (NAME@FP)
  std::vector<ExternalEngine> external;  // one per external id, in engine order
  std::vector<Axis> axes;
  std::vector<Measure> measures;
  std::string hash;  // FNV-1a of the plan's JSON without this field: 16 hex digits

  std::size_t cell_count() const;
  // What to start for engines[i]: a registry name as it is; an external engine's `runs` ("" until
  // `sweep --engine-file` authorised it).
  std::string runs(std::size_t engine) const;
  Cell cell(std::size_t i) const;  // i < cell_count(), in plan order
  bool has(Measure m) const;
};

// The plan of a loaded sweep. Reads every scene and applies each axis value to each (one axis at a
// time): a value that cannot apply is an InputError naming the sweep file, the axis and the scene,
// before any cell runs. Two scenes of one name are refused. `engines`: the declared info of the
// sweep's engines this build has; a step any of them would refuse to run (run_limits.hpp: steps,
// recorded samples' memory, float range) is refused here too.
Plan make_plan(const SweepSpec& sweep, std::span<const EngineInfo> engines = {});

// The hash of a plan's content (FNV-1a over its JSON without the hash and the paths).
std::string plan_hash(const Plan& plan);

// The plan as JSON text (one object, keys in a fixed order, ending in a newline); the same plan
// gives the same bytes.
std::string plan_text(const Plan& plan);

// Reads a plan file written by plan_text. Throws InputError naming the file for anything else: not
// JSON, another format, a hash that does not match its content (an edited plan).
Plan read_plan(const std::string& path);

// The same from the plan's text; `path` names it in messages. With check_hash false a plan whose
// hash does not match is taken as it is (the fuzz target: fuzz/plan_reader_fuzz.cpp).
Plan parse_plan(const std::string& text, const std::string& path, bool check_hash = true);

// The shard (0 .. n-1) of the cell with this key among n: FNV-1a of the key, modulo n.
std::size_t shard_of(std::string_view key, std::size_t n);

// Largest plan file read: 256 MiB.
inline constexpr long long kMaxPlanBytes = 256LL << 20;

}  // namespace dropcheck
