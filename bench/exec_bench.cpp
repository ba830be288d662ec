// The cost of the engine protocol (docs/protocol.md): one step of the seed engine compiled in
// (`ours`, f32) against the same law in C (examples/c/seed_engine.c, f32) driven over the protocol,
// per body-step (items_per_second = body-steps per second). Each iteration is what the runner does
// per step: set_forces, step, read. The difference is the protocol: formatting and parsing %.17g
// numbers, two pipe writes/reads and two context switches per step.
//
// The C engine is found at $DROPCHECK_SEED_ENGINE_C, else ../examples/seed_engine_c next to this
// binary (built by tests/CMakeLists.txt: configure with -DDROPCHECK_BUILD_BENCH=ON and build the
// seed_engine_c target too).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "adapters/exec.hpp"
#include "harness/core/registry.hpp"

namespace {

using namespace dropcheck;

// `bodies` cubes in free flight with damping, side by side.
Scene bench_scene(int bodies) {
  Scene s;
  s.name = "exec_bench";
  s.duration = 1e9;
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.damping_rate = 1.2;
  for (int i = 0; i < bodies; ++i) {
    Body b;
    b.name = "cube" + std::to_string(i);
    b.position = Vec3(2.0 * i, 10.0, 0.0);
    b.velocity = Vec3(1.0, 8.0, 0.0);
    s.bodies.push_back(b);
  }
  return s;
}

std::string seed_engine_c() {
  if (const char* env = std::getenv("DROPCHECK_SEED_ENGINE_C")) return env;
  return (std::filesystem::read_symlink("/proc/self/exe").parent_path().parent_path() / "examples" /
          "seed_engine_c")
      .string();
}

// One runner step per iteration on `engine`, counted per body.
void step_loop(benchmark::State& state, Engine& engine) {
  const Scene scene = bench_scene(static_cast<int>(state.range(0)));
  engine.load(scene, 1.0 / 60.0);
  const std::vector<Vec3> forces(scene.bodies.size(), Vec3(0.5, 0.0, 0.0));
  std::vector<BodyState> out(scene.bodies.size());
  for (auto _ : state) {
    engine.set_forces(forces);
    engine.step();
    engine.read(out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_OursStep(benchmark::State& state) {
  auto engine = make_engine("ours");
  step_loop(state, *engine);
}

void BM_ExecCStep(benchmark::State& state) {
  const std::string path = seed_engine_c();
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(
        ("no C example engine at " + path + " (set DROPCHECK_SEED_ENGINE_C)").c_str());
    return;
  }
  auto engine = make_exec_engine(parse_exec_spec("exec:" + path));
  try {
    step_loop(state, *engine);
  } catch (const EngineError& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

// Wall time (UseRealTime): the engine process works while dropcheck waits, which CPU time misses.
BENCHMARK(BM_OursStep)->Arg(1)->Arg(16)->Arg(256)->UseRealTime();
BENCHMARK(BM_ExecCStep)->Arg(1)->Arg(16)->Arg(256)->UseRealTime();
