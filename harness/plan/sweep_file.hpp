// A sweep file (TOML; docs/sweeps.md): the scenes and engines of a grid, the axes it varies and
// their values, and what each cell measures. `dropcheck plan` turns one into a plan (plan.hpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dropcheck {

// What an axis varies. Named axes act on the scene model (or the step, or the engine's scalar);
// a key axis sets any numeric key of the scene file ("world.linear_drag", "body.cube.mass",
// "force[0].stiffness": axes.hpp).
enum class AxisKind {
  timestep,          // the step h ("1/60" or seconds)
  damping_rate,      // world damping k (1/s)
  gravity,           // |g| (m/s^2), the scene's direction kept (-y when it has none)
  spring_stiffness,  // every spring's stiffness (N/m)
  mass_ratio,        // every dynamic body's mass after the first, as a multiple of the first's
  initial_speed,     // every dynamic body's |v0| (m/s), its direction kept (+y when at rest)
  scalar,            // "f32" or "f64": the engine's build (ours / ours-f64)
  scene_key,         // a numeric key of the scene file
};

struct Axis {
  AxisKind kind = AxisKind::timestep;
  std::string name;                 // the named axis, or the key path for scene_key
  std::vector<std::string> values;  // each value as it appears in cell keys: "1/60", "0.5", "f32"
  int line = 0;                     // its [[axis]] table in the sweep file, for messages
};

// What a cell records besides its status (docs/results.md).
enum class Measure { error, own_law, stability, hash, timing };

// An external engine of a sweep (an engine file or exec:PATH; docs/protocol.md): the id its cells
// carry, NAME@FINGERPRINT (harness/core/registry.hpp: a changed engine is another engine), and
// where it was found. A plan never starts it by itself: `sweep --engine-file FILE` names what runs
// it, checked against the fingerprint (`runs`).
struct ExternalEngine {
  std::string id;
  std::string file;  // "DIR/NAME.toml" or "exec:PATH", resolved from the sweep file's folder
  std::string runs;  // what `sweep` starts for it; "" until a --engine-file of that id is given
};

struct SweepSpec {
  std::string file;
  std::string description;
  std::vector<std::string> scene_files;  // as resolved: a folder gives its *.toml files, sorted
  std::vector<std::string> engines;      // registry names and external engines' ids
  std::vector<ExternalEngine> external;
  std::vector<Axis> axes;
  std::vector<Measure> measures;
};

// Reads and validates a sweep file. Throws InputError naming the file, line, key and problem for
// a syntax error, an unknown key, a scene path that is not a scene file or folder, an engine not
// in `known_engines` nor an engine file or exec:PATH (read and fingerprinted, never started),
// an unknown axis, a range that is not one (count < 1, a log range through 0), an axis given twice,
// or more than kMaxCells cells.
SweepSpec load_sweep(const std::string& path, const std::vector<std::string>& known_engines);

// Largest plan: 2*10^6 cells (a 10^5-cell sweep is a cluster's afternoon; 10^7 is a typo's).
inline constexpr long long kMaxCells = 2'000'000;

const char* to_string(AxisKind kind);
const char* to_string(Measure m);
// The named axis or measure of that name (to_string's inverse; not scene_key): nullopt for others.
std::optional<AxisKind> named_axis(std::string_view name);
std::optional<Measure> measure_named(std::string_view name);

}  // namespace dropcheck
