#include "harness/measure/timing.hpp"

#include <algorithm>
#include <chrono>
#include <variant>

#include "harness/core/runner.hpp"

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

// The engine alone: load, then step() only. An engine that throws ends the loop (its failure is
// the run's business, recorded by run_scene; here it only must not abort the timing).
double time_bare(Engine& engine, const Scene& scene, double h) {
  try {
    engine.load(scene, h);
  } catch (const std::exception&) {
    return 0.0;
  }
  const std::int64_t steps = step_count(scene, h);
  const auto start = Clock::now();
  try {
    for (std::int64_t n = 0; n < steps; ++n) engine.step();
  } catch (const std::exception&) {
  }
  return seconds_since(start);
}

// Doubles the copies until one full run lasts min_run_seconds; a failed run stops the search (a
// failure takes no time and would otherwise drive the copies to max_replicas).
int replicas_needed(const EngineFactory& make, const Scene& scene, double h, const TimingOptions& o) {
  int copies = 1;
  while (copies < o.max_replicas) {
    std::unique_ptr<Engine> e = make();
    const Trajectory run = run_scene(*e, replicate(scene, copies), h);
    if (run.status != RunStatus::ok || run.wall_seconds >= o.min_run_seconds) break;
    copies *= 2;
  }
  return std::min(copies, o.max_replicas);
}

// Width of the scene along x (m), from the lowest to the highest box face of any body.
double x_extent(const Scene& scene) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const double a = b.position.x() - b.half_extents.x(), c = b.position.x() + b.half_extents.x();
    lo = i ? std::min(lo, a) : a;
    hi = i ? std::max(hi, c) : c;
  }
  return hi - lo;
}

}  // namespace

Scene replicate(const Scene& scene, int copies) {
  Scene out = scene;
  const Vec3 step(x_extent(scene) + 10.0, 0.0, 0.0);
  for (int c = 1; c < copies; ++c) {
    const Vec3 offset = step * c;
    const std::size_t first = out.bodies.size();
    for (Body b : scene.bodies) {
      b.name += "#" + std::to_string(c);
      b.position += offset;
      out.bodies.push_back(b);
    }
    for (Force f : scene.forces) {
      for (std::size_t& i : f.bodies) i += first;
      if (auto* s = std::get_if<Spring>(&f.law)) s->anchor += offset;
      out.forces.push_back(f);
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
