// Does the slowdown alert catch a real slowdown? Times every cell of the shipped scenes twice, as
// `dropcheck report` does (time_evaluations), the second time with one engine made 20 % slower,
// and prints which cells the alert (slowdowns(), harness/report/timing_record.hpp) flags: the
// slowed engine's cells it catches, and any other engine's cell it flags (a false alarm).
//
//   dropcheck_slowdown_alert [--engine E] [--percent P] [SCENE_DIR]   (defaults: ours, 20,
//   scenarios)
//
// The slowdown is a test double, SlowedEngine: after each step() of the real engine it does a fixed
// amount of busy work worth P % of that cell's own headline per step, measured in the first pass,
// so the second pass's full loop is about P % slower, and only that engine's. The report line gives
// each flagged cell's measured rise. Wall-clock figures: run it on a
// quiet machine (both passes together: 69 s here).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/core/provenance.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/timestep.hpp"
#include "harness/report/timing_record.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/evaluate.hpp"

namespace dropcheck {
namespace {

using Clock = std::chrono::steady_clock;

// Extra seconds per step by (scene, h): P % of the first pass's headline for one step of the
// replicated run.
using ExtraPerStep = std::map<std::pair<std::string, double>, double>;

// A fixed amount of busy work: `n` dependent additions the compiler cannot drop.
volatile std::uint64_t g_spin_sink = 0;
void spin(std::uint64_t n) {
  std::uint64_t x = g_spin_sink;
  for (std::uint64_t i = 0; i < n; ++i) x = x * 6364136223846793005ull + 1442695040888963407ull;
  g_spin_sink = x;
}

// spin() iterations per second on this machine: the fastest of five 20 ms runs.
double spins_per_second() {
  double best = 0.0;
  for (int k = 0; k < 5; ++k) {
    const std::uint64_t n = 20'000'000;
    const Clock::time_point start = Clock::now();
    spin(n);
    best = std::max(
        best, static_cast<double>(n) / std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

// The engine with a fixed amount of extra work after each step: no clock is read per step (two
// clock reads would cost more than the extra itself in a cheap engine's step).
class SlowedEngine final : public ForwardingEngine {
 public:
  SlowedEngine(std::unique_ptr<Engine> owned, const ExtraPerStep& extra, double rate)
      : ForwardingEngine(*owned), owned_(std::move(owned)), extra_(extra), rate_(rate) {}
  void load(const Scene& scene, double h) override {
    inner_.load(scene, h);
    const auto it = extra_.find({scene.name, h});
    spins_ = static_cast<std::uint64_t>((it == extra_.end() ? 0.0 : it->second) * rate_ + 0.5);
  }
  void step() override {
    inner_.step();
    spin(spins_);
  }

 private:
  std::unique_ptr<Engine> owned_;
  const ExtraPerStep& extra_;
  double rate_;
  std::uint64_t spins_ = 0;
};

std::vector<Scene> shipped(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Scene> out;
  for (const std::string& f : files) out.push_back(load_scene(f));
  return out;
}

TimingRecord time_all(const std::vector<Scene>& scenes, const std::vector<EngineSlot>& slots) {
  std::vector<SceneEvaluation> evaluated;
  for (const Scene& s : scenes) evaluated.push_back(evaluate_scene(s, slots));
  time_evaluations(evaluated, slots);
  return timing_record(evaluated, current_provenance("."), this_machine());
}

int run(int argc, char** argv) {
  std::string slowed = "ours", dir = "scenarios";
  double percent = 20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--engine" && i + 1 < argc)
      slowed = argv[++i];
    else if (a == "--percent" && i + 1 < argc)
      percent = std::stod(argv[++i]);
    else
      dir = a;
  }
  const std::vector<Scene> scenes = shipped(dir);
  std::vector<EngineSlot> slots;
  for (const std::string& name : available_engine_names())
    slots.push_back({name, [name] { return make_engine(name); }, ""});

  std::cerr << "pass 1 of 2: every cell as it is\n";
  const TimingRecord before = time_all(scenes, slots);
  ExtraPerStep extra;
  for (const TimedCell& c : before.cells) {
    if (c.engine != slowed) continue;
    std::string why;
    const double h = parse_timestep(c.h, why)->seconds;
    const double headline_s = c.value({}) * 1e-3;  // per simulated second, per copy
    extra[{c.scene, h}] = percent / 100.0 * headline_s * h * c.replicas;
  }
  const double rate = spins_per_second();
  for (EngineSlot& s : slots)
    if (s.name == slowed)
      s.make = [&extra, slowed, rate] {
        return std::make_unique<SlowedEngine>(make_engine(slowed), extra, rate);
      };
  std::cerr << "pass 2 of 2: " << slowed << " slowed by " << percent << " %\n";
  const TimingRecord after = time_all(scenes, slots);

  std::size_t cells = 0, caught = 0, false_alarms = 0, others = 0;
  for (const TimedCell& c : after.cells) (c.engine == slowed ? cells : others)++;
  for (const Slowdown& s : slowdowns(before, after)) {
    (s.cell.engine == slowed ? caught : false_alarms)++;
    std::cout << "flagged: " << s.cell.scene << " / " << s.cell.engine << " / h = " << s.cell.h
              << printf_string(": rose %.1f %% (threshold %.0f %%)\n", 100.0 * s.cell.moved,
                               100.0 * s.threshold);
  }
  std::cout << printf_string(
      "%s slowed by %.0f %%: %zu of %zu of its cells flagged; %zu of %zu other cells flagged "
      "(false alarms) ⏱\n",
      slowed, percent, caught, cells, false_alarms, others);
  return 0;
}

}  // namespace
}  // namespace dropcheck

int main(int argc, char** argv) {
  return dropcheck::run(argc, argv);
}
