// dropcheck identify SCENE (--engine E | --trajectory CSV) [--dt H]
// On a slide to a stop: the engine's friction model (harness/oracles/identify_friction.hpp).
// Otherwise names the discrete law behind a free-flight trajectory (harness/oracles/identify.hpp):
// fits every member of the family with its own phi and g, prints each member's residual, and the
// best fit, or that none fits within 2 cm, or that two fit equally. With --engine, the engine's run
// at the scene's step (or --dt) is used and compared with the law it declares. Exit 0: one member
// named (and, with --engine, it is the declared one); 1: no member fits, two fit equally, the
// declared law is not the one found, or the engine's run failed; 2: bad input.
//
// Argument parsing (IdentifyRequest, parse_identify_request) is kept apart from the work
// (run_identify) so that the CLI front end can change without touching the analysis.
#include <cmath>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/trajectory_csv.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/identify.hpp"
#include "harness/oracles/identify_friction.hpp"
#include "harness/oracles/identify_rotation.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/accuracy_response.hpp"
#include "harness/study/closed_form_order.hpp"
#include "selection.hpp"

namespace dropcheck {

const CommandSpec& identify_spec() {
  static const CommandSpec spec{
      "identify",
      "Names the fixed-step law behind a free-flight trajectory: fits every member of the law "
      "family (the Euler members: where damping sits, semi-implicit or explicit position update; "
      "and RK4) with its own per-step damping factor and gravity, and prints each member's "
      "residual and the best fit; with --engine, also the order of convergence measured at 2h, "
      "h and h/2 against the closed form. An error-controlled engine (simbody-rkm) has no "
      "fixed-step member: with --engine it gets its error against the closed form at accuracies "
      "1e-3 to 1e-12 instead, each against that accuracy's budget. On a slide to a stop (with "
      "--engine): the engine's friction model (cone, box pyramid or sum pyramid) from the ratio "
      "of its stop distances at 45 and at 0 degrees.",
      "scene FILE",
      "the scene file (.toml) the trajectory comes from",
      1,
      1,
      {{"--engine", "E", "run engine E on the scene and identify its law"},
       {"--trajectory", "CSV", "identify the one run in CSV (dropcheck's trajectory CSV format)"},
       {"--dt", "H", "with --engine: the step (default: the scene's)"},
       {"--combine", "",
        "on a slide, with --engine: also the rule the engine combines two bodies' friction by "
        "(the cube 0.2, the floor 0.8, each passed to the engine verbatim)"}}};
  return spec;
}

namespace {

struct IdentifyRequest {
  std::string scene_file;
  std::string engine;      // --engine E, or empty
  std::string trajectory;  // --trajectory CSV, or empty
  std::string dt;          // --dt H (with --engine), or empty for the scene's step
  bool combine = false;    // --combine
};

IdentifyRequest parse_identify_request(const std::vector<std::string>& argv) {
  const Args args = parse_args(identify_spec(), argv);
  IdentifyRequest r{args.positional[0], args.value("--engine"), args.value("--trajectory"),
                    args.value("--dt"), args.has("--combine")};
  if (r.combine && r.engine.empty())
    throw InputError("", 0, "--combine", "applies to --engine only");
  if (r.engine.empty() == r.trajectory.empty())
    throw InputError("", 0, "identify", "expects exactly one of --engine E and --trajectory CSV");
  if (!r.dt.empty() && r.engine.empty())
    throw InputError("", 0, "--dt", "applies to --engine only");
  return r;
}

// The one run in a trajectory file, checked against the scene's name.
Trajectory trajectory_from_file(const std::string& file) {
  std::vector<Trajectory> runs = read_trajectories_csv(file);
  if (runs.size() != 1) {
    std::string list;
    for (const Trajectory& t : runs)
      list += (list.empty() ? "" : ", ") + t.engine + " at dt " + sig(t.h, 6);
    throw InputError(file, 0, "",
                     "holds " + std::to_string(runs.size()) + " runs (" + list +
                         "); identify reads one: dropcheck run SCENE --engine E --csv OUT");
  }
  return runs[0];
}

// A Gazebo benchmark log names its models model_0, model_1, ...: read as the scene's dynamic
// bodies, in order, when there are as many (said on `out`).
void adopt_scene_names(Trajectory& run, const Scene& scene, std::ostream& out) {
  std::vector<std::string> dynamic;
  for (const Body& b : scene.bodies)
    if (!b.is_static) dynamic.push_back(b.name);
  if (dynamic.size() != run.bodies() || dynamic.size() != scene.bodies.size()) return;
  for (std::size_t i = 0; i < run.bodies(); ++i)
    if (run.body_names[i] != "model_" + std::to_string(i)) return;
  for (std::size_t i = 0; i < run.bodies(); ++i) {
    out << "reading " << run.body_names[i] << " as body '" << dynamic[i] << "'\n";
    run.body_names[i] = dynamic[i];
  }
}

void print_fits(const Identification& id, std::ostream& out) {
  out << printf_string("  %-24s %-38s %12s  %-32s %14s %14s\n", "member", "update", "phi",
                       "gravity (m/s^2)", "max|x-fit| m", "max|v-fit| m/s");
  for (const MemberFit& m : id.fits) {
    const std::string g =
        printf_string("(%.6g, %.6g, %.6g)", m.gravity.x(), m.gravity.y(), m.gravity.z());
    out << printf_string("  %-24s %-38s %12.9f  %-32s %14.3g %14.3g\n", law_key(m.law).c_str(),
                         to_string(m.law).c_str(), m.phi, g.c_str(), m.max_dx, m.max_dv);
  }
}

// Why two members can tie, for the ambiguity message.
std::string hint(const Identification& id) {
  const Law a = id.fits[id.best].law, b = id.fits[id.runner_up].law;
  if (std::abs(id.fits[id.best].phi - 1.0) < 1e-6)
    return " (without damping, phi = 1, where the damping sits leaves no trace: use a scene with "
           "damping)";
  const auto semi = [](Law l, DampingOrder d) { return l == Law{d, PositionUpdate::SemiImplicit}; };
  if ((semi(a, DampingOrder::AfterForces) && semi(b, DampingOrder::BeforeForces)) ||
      (semi(b, DampingOrder::AfterForces) && semi(a, DampingOrder::BeforeForces)))
    return " (with g fitted, after-forces with gravity g is before-forces with gravity phi*g "
           "unless a "
           "force differs between bodies: use e.g. scenarios/wind.toml)";
  return "";
}

// The verdict line(s); true when one member is named.
bool print_verdict(const Identification& id, std::ostream& out) {
  const MemberFit& best = id.fits[id.best];
  const MemberFit& next = id.fits[id.runner_up];
  if (!id.fits_any) {
    out << "no member fits better than 2 cm: not a fixed-step scheme of the family (closest: "
        << law_key(best.law) << " at " << g3(best.max_dx) << " m)\n";
    return false;
  }
  if (id.ambiguous) {
    out << "ambiguous: " << law_key(best.law) << " (" << g3(best.max_dx) << " m) and "
        << law_key(next.law) << " (" << g3(next.max_dx)
        << " m) fit equally well: this scene cannot tell them apart" << hint(id) << "\n";
    return false;
  }
  out << "best fit: " << law_key(best.law) << " (" << to_string(best.law) << ")"
      << printf_string(": residual %.3g m, phi = %.9g, ", best.max_dx, best.phi)
      << printf_string("g = (%.6g, %.6g, %.6g); runner-up ", best.gravity.x(), best.gravity.y(),
                       best.gravity.z())
      << law_key(next.law) << " at " << g3(next.max_dx) << " m\n";
  return true;
}

// A rotational member and, when the scene's angular damping shows it, where the damping sits, or
// that it turns with the step-start angular velocity.
std::string rotation_member(const RotationFit& f, bool damping_seen) {
  // The semi-implicit member's key names the damping's place alone ("after-forces").
  if (damping_seen) return rotation_law_key(f.law) + ", " + law_key(f.linear);
  const bool explicit_turn = f.linear.position == PositionUpdate::Explicit;
  return rotation_law_key(f.law) + (explicit_turn ? ", step-start w" : "");
}

// The rotational fits and verdict; true when one member is named. `declared` (with --engine)
// is checked against the member found.
bool print_rotation(const RotationIdentification& id, const std::optional<EngineInfo>& declared,
                    std::ostream& out) {
  out << "rotation: every member replayed from the first sample"
      << (id.damping_seen ? ", with each placement of the angular damping"
                          : " (no angular damping: where it sits leaves no trace)")
      << "\n"
      << printf_string("  %-52s %16s %18s\n", "member", "max angle rad", "max|w-fit| rad/s");
  for (const RotationFit& f : id.fits)
    out << printf_string("  %-52s %16.3g %18.3g\n", rotation_member(f, id.damping_seen).c_str(),
                         f.max_angle, f.max_dw);
  const RotationFit& best = id.fits[id.best];
  const RotationFit& next = id.fits[id.runner_up];
  bool ok = false;
  if (!id.fits_any) {
    out << "no rotational member fits within " << g3(kIdentifyRotationTolerance)
        << " rad (closest: " << rotation_member(best, id.damping_seen) << " at "
        << g3(best.max_angle) << " rad)\n";
  } else if (id.ambiguous) {
    out << "ambiguous: " << rotation_member(best, id.damping_seen) << " (" << g3(best.max_angle)
        << " rad) and " << rotation_member(next, id.damping_seen) << " (" << g3(next.max_angle)
        << " rad) fit equally well: this scene cannot tell them apart (a spin about a principal "
           "axis has no gyroscopic term: use a tumbling body)\n";
  } else {
    out << "best fit: " << rotation_member(best, id.damping_seen) << " (" << to_string(best.law)
        << "): " << g3(best.max_angle) << " rad, |w - fit| " << g3(best.max_dw)
        << " rad/s; runner-up " << rotation_member(next, id.damping_seen) << " at "
        << g3(next.max_angle) << " rad\n";
    ok = true;
  }
  if (!declared) return ok;
  const RotationFit want{declared->rotation_law, declared->law};
  const auto same = [&](const RotationFit& f) {
    return f.law == want.law && f.linear.position == want.linear.position &&
           (!id.damping_seen || law_difference(f.linear, want.linear).empty());
  };
  const bool match = ok && same(best);
  bool tied = false;  // the declared member fits as well as the best (within the 2x of ambiguity)
  for (const RotationFit& f : id.fits)
    tied = tied || (same(f) && f.max_angle <= 2.0 * best.max_angle + 1e-12);
  out << "declared rotation " << rotation_member(want, id.damping_seen) << ": "
      << (match                  ? "matches"
          : id.ambiguous && tied ? "one of the equal fits (not confirmed)"
                                 : "MISMATCH")
      << "\n";
  return match;
}

// The engine's observed order against the closed form and whether it is its declared law's;
// false only when an order was measured and it is not.
bool print_order(const ClosedFormOrder& o, Law declared, std::ostream& out) {
  const int want = order_of(declared);
  if (!o.unavailable.empty()) {
    out << "order: not measured: " << o.unavailable << "\n";
    return true;
  }
  bool match = true;
  for (double p : o.estimate.orders) match = match && order_matches(p, want);
  out << "order against the closed form: " << o.estimate.text
      << (o.dropped.empty() ? "" : " (left out: " + o.dropped + ")") << "; declared "
      << law_key(declared) << " is order " << want << ": " << (match ? "matches" : "MISMATCH")
      << "\n";
  return match;
}

// An error-controlled engine is not fitted to a discrete member (law.hpp: it has none); its error
// against the closed form is printed per accuracy, each against its budget. True when within all.
bool print_accuracy_response(const AccuracyResponse& a, const EngineInfo& info, std::ostream& out) {
  out << "declared " << law_key(info.law) << " (" << to_string(info.law)
      << "): not fitted to a discrete member; its law is the continuous model, judged against "
         "the closed form within each accuracy's budget\n";
  if (!a.unavailable.empty()) {
    out << "error per accuracy: not measured: " << a.unavailable << "\n";
    return false;
  }
  out << printf_string("  %-10s %16s %16s %14s %14s\n", "accuracy", "max|x - exact| m",
                       "max|v - exact|", "engine steps", "budget x m");
  for (const AccuracyPoint& p : a.points)
    out << printf_string("  %-10.3g %16.3g %16.3g %14lld %14.3g%s\n", p.accuracy, p.error_x,
                         p.error_v, static_cast<long long>(p.engine_steps), p.budget_x,
                         p.within() ? "" : "  OUTSIDE");
  out << "error per accuracy: "
      << (a.within() ? "within the budget at every accuracy" : "OUTSIDE the budget") << "\n";
  return a.within();
}

// An engine for identifying friction on `s`: the one `dropcheck check` would run, or, when its
// adapter does not map the scene's friction, the engine with each body's own coefficient passed
// verbatim (Engine::use_body_materials: its combine rule makes the pair's; `raw` says so). Throws
// InputError, with the reason, when neither can run the scene.
std::unique_ptr<Engine> friction_engine(const std::string& name, const Scene& s, bool& raw) {
  std::vector<SelectedEngine> engines = select_engines({name}, s);
  raw = false;
  if (engines[0].engine) return std::move(engines[0].engine);
  Scene plain = s;  // the scene as the engine would take it without the friction it cannot map
  for (Body& b : plain.bodies) b.friction.reset();
  std::unique_ptr<Engine> e = make_engine(name);
  if (!e || !e->cannot_run(plain).empty() || !e->use_body_materials())
    throw InputError("", 0, "--engine " + name, engines[0].skipped_because);
  raw = true;
  return e;
}

// A slide to a stop: the engine's friction model from its stop distances at 0 and 45 degrees
// (harness/oracles/identify_friction.hpp), against the model it declares when its adapter maps
// friction.
int identify_friction_model(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  if (r.engine.empty())
    throw InputError("", 0, "--trajectory",
                     "a slide is identified from two runs, at 0 and 45 degrees: use --engine E");
  const SlidePair pair = slide_pair(scene);
  if (const std::unique_ptr<Engine> e = make_engine(r.engine);
      e && e->info().capabilities.planar_only) {
    out << "friction model: not applicable: " << e->info().name
        << " is a 2-D engine, with one tangent direction (a cone and the pyramids coincide)\n";
    return kExitOk;
  }
  double distance[2] = {0.0, 0.0};
  double h = 0.0;
  std::optional<double> mu;
  std::string name;
  bool raw = false;
  FrictionModel declared = FrictionModel::cone;
  for (int k = 0; k < 2; ++k) {
    const Scene& s = k == 0 ? pair.along_axis : pair.diagonal;
    std::unique_ptr<Engine> engine = friction_engine(r.engine, s, raw);
    name = engine->info().name;
    declared = engine->info().friction_model;
    h = step_from_flag(r.dt, s).seconds;
    const Trajectory run = run_scene(*engine, s, h);
    if (run.status != RunStatus::ok) {
      out << "identify " << scene.name << ": the run of " << run.engine << " failed at step "
          << run.failed_step << " (" << to_string(run.status) << "): " << run.failure << "\n";
      return kExitCheckFailed;
    }
    // The distance to the stop, or to the run's end for an engine that creeps on (Bullet ends at
    // 9e-5 m/s); a slide still above 1 % of its launch speed at the end has no distance yet.
    const SlideSetup slide = slide_setups(s).at(0);
    const SlidePath path = observed_slide_path(run, slide);
    const SlideObservation seen = observe_slide(path, tolerance::kStoppedSpeed);
    if (observe_slide(path, 0.01 * slide.v0).stop_step < 0) {
      out << "identify " << scene.name << ": " << run.engine << "'s slide at "
          << (k == 0 ? "0" : "45") << " degrees still slides at the run's end ("
          << printf_string("%.7g m", seen.distance) << "): no ratio; lengthen the scene\n";
      return kExitCheckFailed;
    }
    distance[k] = seen.distance;
    if (raw && k == 0) mu = pair_friction(s, run);
  }
  const FrictionIdentification id = identify_friction(scene, h, distance[0], distance[1], mu);
  out << "identify " << scene.name << ": " << name << "'s friction from its slides at 0 and 45 "
      << "degrees"
      << (raw ? printf_string(" (each body's own coefficient: the pair's %.5g)", *mu)
              : std::string())
      << "\nfriction model: " << id.sentence() << "\n";
  if (raw) {
    out << "declared: none (its adapter does not map friction)\n";
    return id.named ? kExitOk : kExitCheckFailed;
  }
  out << "declared " << to_string(declared) << ": "
      << (id.named == declared ? "matches" : "MISMATCH") << "\n";
  return id.named == declared ? kExitOk : kExitCheckFailed;
}

// The engine's combine rule for friction (harness/oracles/identify_friction.hpp): the slide with
// each body's coefficient passed verbatim. It runs outside the capability check on purpose: what
// is asked is the engine's own rule, which an adapter that maps the scene's value hides.
int identify_combine_rule(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  std::unique_ptr<Engine> engine = make_engine(r.engine);
  if (!engine) throw InputError("", 0, "--engine " + r.engine, engine_unavailable_reason(r.engine));
  const std::string name = engine->info().name;
  if (!engine->use_body_materials()) {
    out << "combine rule: not identified: " << name
        << "'s adapter sets each pair's friction itself (the engine has no per-body material)\n";
    return kExitOk;
  }
  const Scene combined = combine_scene(scene);
  const Trajectory run = run_scene(*engine, combined, step_from_flag(r.dt, combined).seconds);
  if (run.status != RunStatus::ok) {
    out << "combine rule: the run of " << name << " failed at step " << run.failed_step << " ("
        << to_string(run.status) << "): " << run.failure << "\n";
    return kExitCheckFailed;
  }
  const CombineIdentification id = identify_combine(combined, run);
  out << "combine rule: " << id.sentence() << "\n";
  return id.named ? kExitOk : kExitCheckFailed;
}

int run_identify(const IdentifyRequest& r, std::ostream& out) {
  const Scene scene = load_scene(r.scene_file);
  if (r.combine && slide_setups(scene).empty())
    throw InputError(r.scene_file, 0, "--combine",
                     "applies to a slide to a stop (docs/contact.md)");
  if (r.combine) {
    const int rule = identify_combine_rule(scene, r, out);
    return std::max(rule, identify_friction_model(scene, r, out));
  }
  if (!slide_setups(scene).empty()) return identify_friction_model(scene, r, out);
  Trajectory run;
  std::optional<Law> declared;
  std::optional<EngineInfo> declared_info;
  std::unique_ptr<Engine> engine;
  if (!r.engine.empty()) {
    std::vector<SelectedEngine> engines = select_engines({r.engine}, scene);
    if (!engines[0].engine)
      throw InputError("", 0, "--engine " + r.engine, engines[0].skipped_because);
    engine = std::move(engines[0].engine);
    declared_info = engine->info();
    declared = declared_info->law;
    const double h = step_from_flag(r.dt, scene).seconds;
    if (declared->scheme == Scheme::ErrorControlled) {
      out << "identify " << scene.name << ": " << declared_info->name << " at h = " << sig(h, 9)
          << " s\n";
      const bool within =
          print_accuracy_response(error_per_accuracy(*engine, scene, h), *declared_info, out);
      return within ? kExitOk : kExitCheckFailed;
    }
    run = run_scene(*engine, scene, h);
    if (run.status != RunStatus::ok) {
      out << "identify " << scene.name << ": the run of " << run.engine << " failed at step "
          << run.failed_step << " (" << to_string(run.status) << "): " << run.failure << "\n";
      return kExitCheckFailed;
    }
  } else {
    run = trajectory_from_file(r.trajectory);
    adopt_scene_names(run, scene, out);
  }
  const Identification id = identify_law(scene, run);
  out << "identify " << scene.name << ": trajectory of " << run.engine << ", " << run.bodies()
      << " bodies, " << run.steps << " steps"
      << " at h = " << sig(run.h, 9) << " s\n";
  print_fits(id, out);
  bool ok = print_verdict(id, out);
  if (declared) {
    const bool match = ok && id.fits[id.best].law == *declared;
    const bool tied = id.ambiguous &&
                      (id.fits[id.best].law == *declared || id.fits[id.runner_up].law == *declared);
    out << "declared " << law_key(*declared) << ": "
        << (match  ? "matches"
            : tied ? "one of the equal fits (not confirmed)"
                   : "MISMATCH")
        << "\n";
    ok = ok && match;
    ok = print_order(order_against_closed_form(*engine, scene, run.h), *declared, out) && ok;
  }
  if (run.rotates)
    ok = print_rotation(identify_rotation(scene, run), declared_info, out) && ok;
  else if (needs_rotation(scene))
    out << "rotation: the trajectory carries no rotation columns (qw..wz): its rotational law is "
           "not identified\n";
  return ok ? kExitOk : kExitCheckFailed;
}

}  // namespace

int cmd_identify(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  return run_identify(parse_identify_request(argv), out);
}

}  // namespace dropcheck
