#include "harness/study/identify_contact.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/slide_verdict.hpp"
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

// Every slide of `scene` in `run` judged as `dropcheck check` judges an engine declaring `info`:
// follows when each does; the detail names the first slide that does not, or the largest distance.
ContactMemberFit slide_member_fit(const Trajectory& run, const Scene& scene, const EngineInfo& info,
                                  double h, const std::string& member) {
  ContactMemberFit fit{member, {}, true, true, ""};
  double worst = 0.0;
  std::string bound;  // a member held by momentum: its certificate, not a path
  for (const SlideSetup& s : slide_setups(scene)) {
    const SlideVerdict v = judge_slide(run, scene, s, info, h);
    const std::string& body = scene.bodies[s.body].name;
    if (!v.exact) {
      fit.judged = fit.follows = false;
      fit.detail = body + ": " + v.not_judged;
      return fit;
    }
    worst = std::max(worst, v.off_law);
    if (v.coulomb)
      bound = printf_string("its median slipping step's friction %.7g of mu*N (bound %.0e)",
                            v.coulomb->median_ratio, info.contact_solver.coulomb_median_bound);
    if (!v.follows && fit.follows) {
      fit.follows = false;
      fit.detail = printf_string("%s departs at step %lld, %.3g m off it by the end", body.c_str(),
                                 static_cast<long long>(v.first_off), v.off_law);
    }
  }
  if (fit.follows) fit.detail = bound.empty() ? printf_string("its path to %.2g m", worst) : bound;
  return fit;
}

// The replayed members an adapter declares, each once with the engines declaring it, and an
// iterative one's neighbours in iteration count.
std::vector<std::pair<ContactSolver, std::vector<std::string>>> replayed_members() {
  std::vector<std::pair<ContactSolver, std::vector<std::string>>> out;
  const auto add = [&](const ContactSolver& solver, const std::string& engine) {
    auto same = std::find_if(out.begin(), out.end(),
                             [&](const auto& m) { return describe(m.first) == describe(solver); });
    if (same == out.end()) same = out.emplace(out.end(), solver, std::vector<std::string>{});
    if (!engine.empty()) same->second.push_back(engine);
  };
  for (const EngineInfo& info : declared_members())
    if (replayed(info.contact_solver)) add(info.contact_solver, info.name);
  const std::size_t declared = out.size();
  for (std::size_t i = 0; i < declared; ++i) {
    const ContactSolver solver = out[i].first;
    if (solver.velocity_iterations == 0) continue;
    for (const double f : {0.25, 0.5, 2.0, 4.0}) {
      ContactSolver other = solver;
      other.velocity_iterations =
          std::max(1, static_cast<int>(std::lround(f * solver.velocity_iterations)));
      add(other, "");
    }
  }
  return out;
}

}  // namespace

ContactLawIdentity identify_contact_solver(const Scene& scene, Engine& engine, double h) {
  ContactLawIdentity id;
  const std::optional<Trajectory> run = identity_run(id, scene, engine, h, "contact solver");
  const EngineInfo own = engine.info();
  id.declared = describe(own.contact_solver);
  if (!run) return id;
  id.fits.push_back(slide_member_fit(*run, scene, own, h, id.declared));
  for (const auto& [solver, engines] : replayed_members()) {
    if (describe(solver) == id.declared) continue;
    EngineInfo member = own;
    member.contact_solver = solver;
    ContactMemberFit fit = slide_member_fit(*run, scene, member, h, describe(solver));
    fit.declared_by = engines;
    id.fits.push_back(std::move(fit));
  }
  if (own.contact_solver.kind != ContactSolverKind::exact) {
    EngineInfo exact = own;
    exact.contact_solver = {};
    ContactMemberFit fit = slide_member_fit(*run, scene, exact, h, describe(exact.contact_solver));
    for (const EngineInfo& info : declared_members())
      if (info.capabilities.friction && info.contact_solver.kind == ContactSolverKind::exact)
        fit.declared_by.push_back(info.name);
    id.fits.push_back(std::move(fit));
  }
  return id;
}

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
  // The declared member first, then the ideal law and the declared member with its contact
  // resolved after the position update (a neighbour no adapter declares), then every other
  // adapter's, each once with the engines that declare it.
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
  BounceLaw late = own.bounce_law;
  late.resolved_after_position = true;
  add(late, "");
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
