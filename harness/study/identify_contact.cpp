#include "harness/study/identify_contact.hpp"

#include <algorithm>

#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/turned_verdict.hpp"
#include "harness/oracles/replayed_contact.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

// Every adapter of this build, for the members they declare.
std::vector<EngineInfo> declared_members() {
  std::vector<EngineInfo> out;
  for (const std::string& name : available_engine_names())
    if (std::unique_ptr<Engine> e = make_engine(name)) out.push_back(e->info());
  return out;
}

// The run of `engine` on `scene` at h, every step kept, with its identity's head filled.
std::optional<Trajectory> identity_run(ContactLawIdentity& id, const Scene& scene, Engine& engine,
                                       double h, const char* family) {
  id.scene = scene.name;
  id.engine = engine.info().name;
  id.family = family;
  id.h = h;
  Trajectory run = run_scene(engine, scene, h);
  id.failed = run_failure(run, id.engine);
  if (id.failed) return std::nullopt;
  return run;
}

std::string bounce_detail(const BounceVerdict& v) {
  if (v.follows)
    return v.step_gap < 0.0
               ? printf_string("its path to %.2g m", v.worst_gap)
               : printf_string("every step to %.2g m and %.2g m/s", v.step_gap, v.step_speed);
  return printf_string("departs at step %lld (largest gap %.3g m at step %lld)",
                       static_cast<long long>(v.first_step), v.worst_gap,
                       static_cast<long long>(v.worst_step));
}

}  // namespace

ContactLawIdentity identify_bounce_law(const Scene& scene, Engine& engine, double h) {
  ContactLawIdentity id;
  const std::optional<Trajectory> run = identity_run(id, scene, engine, h, "bounce law");
  const EngineInfo own = engine.info();
  id.declared = describe(own.bounce_law);
  if (!run) return id;
  const BounceSetup setup = bounce_setups(scene).at(0);
  if (replayed(own.contact_solver)) {
    // Its own solver, replayed, is its declared member.
    const BounceVerdict v = judge_bounce(*run, scene, setup, own, h);
    id.declared = describe(own.contact_solver) + ", replayed";
    id.fits.push_back({id.declared, {own.name}, v.not_judged.empty(), v.follows, bounce_detail(v)});
  }
  // The declared member first, then the ideal law, then every other adapter's, each once with
  // the engines that declare it.
  std::vector<std::pair<BounceLaw, std::vector<std::string>>> members;
  const auto add = [&](const BounceLaw& law, const std::string& engine) {
    auto same = std::find_if(members.begin(), members.end(),
                             [&](const auto& m) { return describe(m.first) == describe(law); });
    if (same == members.end())
      same = members.emplace(members.end(), law, std::vector<std::string>{});
    if (!engine.empty()) same->second.push_back(engine);
  };
  add(own.bounce_law, "");
  add(kIdealBounce, "");
  // A replayed solver's engine declares no member of the law: its replay is its law.
  for (const EngineInfo& info : declared_members())
    if (info.capabilities.restitution && !replayed(info.contact_solver))
      add(info.bounce_law, info.name);
  for (const auto& [law, engines] : members) {
    const BounceVerdict v = judge_bounce(*run, setup, law, h);
    id.fits.push_back({describe(law), engines, true, v.follows, bounce_detail(v)});
  }
  return id;
}

ContactLawIdentity identify_turned_contact(const Scene& scene, Engine& engine, double h) {
  ContactLawIdentity id;
  const std::optional<Trajectory> run =
      identity_run(id, scene, engine, h, "turned-box contact law");
  EngineInfo info = engine.info();
  id.declared = describe(info.turned_contact);
  if (!run) return id;
  std::vector<std::string> declaring;
  for (const EngineInfo& other : declared_members())
    if (other.turned_contact == TurnedContact::mean_corner) declaring.push_back(other.name);
  info.turned_contact = TurnedContact::mean_corner;
  const TurnedVerdict v = judge_turned_contact(scene, info, *run);
  id.undeclared = engine.info().turned_contact == TurnedContact::not_declared;
  id.fits.push_back({describe(TurnedContact::mean_corner), declaring, v.not_judged.empty(),
                     v.follows(), v.sentence()});
  return id;
}

}  // namespace dropcheck
