#include "timing.hpp"

#include <algorithm>
#include <chrono>

#include "runner.hpp"

namespace dropcheck {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The full harness loop (forces, step, read, sampling every step) as run_scene does it.
double time_full(Engine& engine, const Scene& scene, double h) {
  return run_scene(engine, scene, h).wall_seconds;
}

// The engine alone: load, then step() only.
double time_bare(Engine& engine, const Scene& scene, double h) {
  engine.load(scene, h);
  const std::int64_t steps = step_count(scene, h);
  const auto start = Clock::now();
  for (std::int64_t n = 0; n < steps; ++n) engine.step();
  return seconds_since(start);
}

int replicas_needed(const EngineFactory& make, const Scene& scene, double h, const TimingOptions& o) {
  int copies = 1;
  while (copies < o.max_replicas) {
    std::unique_ptr<Engine> e = make();
    if (time_full(*e, replicate(scene, copies), h) >= o.min_run_seconds) break;
    copies *= 2;
  }
  return std::min(copies, o.max_replicas);
}

}  // namespace

Scene replicate(const Scene& scene, int copies) {
  Scene out = scene;
  const std::size_t n = scene.bodies.size();
  for (int c = 1; c < copies; ++c) {
    for (std::size_t i = 0; i < n; ++i) {
      if (scene.bodies[i].is_static) continue;
      Body b = scene.bodies[i];
      b.name += "#" + std::to_string(c);
      b.position.z() += 10.0 * c;
      out.bodies.push_back(b);
      for (Force& f : out.forces)
        if (std::find(f.bodies.begin(), f.bodies.end(), i) != f.bodies.end())
          f.bodies.push_back(out.bodies.size() - 1);
    }
  }
  return out;
}

std::vector<Timing> time_engines(const std::vector<std::pair<std::string, EngineFactory>>& engines,
                                 const Scene& scene, double h, const TimingOptions& options) {
  const std::size_t ne = engines.size();
  std::vector<Timing> out(ne);
  std::vector<Scene> scenes(ne);
  std::vector<std::vector<double>> full(ne), bare(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    out[e].engine = engines[e].first;
    out[e].h = h;
    out[e].replicas = replicas_needed(engines[e].second, scene, h, options);
    scenes[e] = replicate(scene, out[e].replicas);
  }
  for (int r = -options.warmups; r < options.repeats; ++r) {
    for (std::size_t k = 0; k < ne; ++k) {
      const std::size_t e = (r % 2 == 0) ? k : ne - 1 - k;  // alternate the order every repeat
      std::unique_ptr<Engine> engine = engines[e].second();
      const double f = time_full(*engine, scenes[e], h);
      const double b = time_bare(*engine, scenes[e], h);
      if (r >= 0) full[e].push_back(f), bare[e].push_back(b);
    }
  }
  for (std::size_t e = 0; e < ne; ++e) {
    const double per = 1.0 / (scene.duration * out[e].replicas);
    out[e].min_per_sim_s = *std::min_element(full[e].begin(), full[e].end()) * per;
    out[e].median_per_sim_s = median(full[e]) * per;
    out[e].bare_min_per_sim_s = *std::min_element(bare[e].begin(), bare[e].end()) * per;
  }
  return out;
}

}  // namespace dropcheck
