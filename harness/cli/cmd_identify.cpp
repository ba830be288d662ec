// dropcheck identify SCENE (--engine E | --trajectory CSV) [--dt H]
// On a slide: the engine's friction model (harness/oracles/identify_friction.hpp) and the contact
// solver its run follows (harness/study/identify_contact.hpp).
// Otherwise names the discrete law behind a free-flight trajectory (harness/oracles/identify.hpp):
// fits every member of the family with its own phi and g, prints each member's residual, and the
// best fit, or that none fits within 2 cm, or that two fit equally. With --engine, the engine's run
// at the scene's step (or --dt) is used and compared with the law it declares. Exit 0: one member
// named (and, with --engine, it is the declared one); 1: no member fits, two fit equally, the
// declared law is not the one found, or the engine's run failed; 2: bad input.
//
// Argument parsing (IdentifyRequest, parse_identify_request) is kept apart from the work
// (run_identify) so that the CLI front end can change without touching the analysis; the analysis
// is computed in harness/study/identify_analysis.hpp, and this file only writes it out.
#include <cmath>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/trajectory_csv.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/identify_analysis.hpp"
#include "harness/study/identify_contact.hpp"
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
      "1e-3 to 1e-12 instead, each against that accuracy's budget. On a slide (with --engine): "
      "the engine's friction model (cone, box pyramid or sum pyramid) from its distances at 45 "
      "and at 0 degrees, to the stop on a level floor, by the run's end on a ramp; then the "
      "contact "
      "solver its run follows among those dropcheck replays (Box2D's and Chipmunk's iterations, "
      "MuJoCo's soft contact, Simbody's force law) and the exact clamp law. On a bounce or "
      "a tumbling landing (with "
      "--engine): the member of the bounce law or the turned-box contact law its run follows, "
      "tried against the ideal law and every member this build's adapters declare.",
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

// A Gazebo benchmark log names its models model_0, model_1, ...: the scene's dynamic bodies, in
// order, when there are as many; else none.
std::vector<std::string> scene_names_for(const Trajectory& run, const Scene& scene) {
  std::vector<std::string> dynamic;
  for (const Body& b : scene.bodies)
    if (!b.is_static) dynamic.push_back(b.name);
  if (dynamic.size() != run.bodies() || dynamic.size() != scene.bodies.size()) return {};
  for (std::size_t i = 0; i < run.bodies(); ++i)
    if (run.body_names[i] != "model_" + std::to_string(i)) return {};
  return dynamic;
}

// Reads a Gazebo log's models as the scene's bodies (scene_names_for), said on `out`.
void adopt_scene_names(Trajectory& run, const Scene& scene, std::ostream& out) {
  const std::vector<std::string> names = scene_names_for(run, scene);
  for (std::size_t i = 0; i < names.size(); ++i) {
    out << "reading " << run.body_names[i] << " as body '" << names[i] << "'\n";
    run.body_names[i] = names[i];
  }
}

// The word for a declaration against what was found.
const char* match_word(DeclaredMatch m) {
  switch (m) {
    case DeclaredMatch::matches:
      return "matches";
    case DeclaredMatch::tied:
      return "one of the equal fits (not confirmed)";
    case DeclaredMatch::mismatch:
      return "MISMATCH";
  }
  return "MISMATCH";
}

const char* match_word(bool matches) {
  return match_word(matches ? DeclaredMatch::matches : DeclaredMatch::mismatch);
}

// "the run of bullet failed at step 12 (non-finite): ...".
std::string failure_text(const RunFailure& f) {
  return "the run of " + f.engine + " failed at step " + std::to_string(f.step) + " (" +
         to_string(f.status) + "): " + f.failure;
}

void print_fits(const Identification& id, std::ostream& out) {
  out << printf_string("  %-24s %-38s %12s  %-32s %14s %14s\n", "member", "update", "phi",
                       "gravity (m/s^2)", "max|x-fit| m", "max|v-fit| m/s");
  for (const MemberFit& m : id.fits) {
    const std::string phi = m.determined ? printf_string("%12.9f", m.phi) : "undetermined";
    const std::string g = m.determined ? printf_string("(%.6g, %.6g, %.6g)", m.gravity.x(),
                                                       m.gravity.y(), m.gravity.z())
                                       : "undetermined";
    out << printf_string("  %-24s %-38s %12s  %-32s %14.3g %14.3g\n", law_key(m.law).c_str(),
                         to_string(m.law).c_str(), phi.c_str(), g.c_str(), m.max_dx, m.max_dv);
  }
}

// The tied members, each with its residual: "a (r m), b (r m) and c (r m)".
std::string tied_fits(const Identification& id) {
  std::string out;
  for (std::size_t i = 0; i < id.tied.size(); ++i) {
    const MemberFit& m = id.fits[id.tied[i]];
    out += (i == 0                    ? ""
            : i + 1 == id.tied.size() ? " and "
                                      : ", ") +
           law_key(m.law) + " (" + g3(m.max_dx) + " m)";
  }
  return out;
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

// The verdict line.
void print_verdict(const Identification& id, std::ostream& out) {
  const MemberFit& best = id.fits[id.best];
  const MemberFit& next = id.fits[id.runner_up];
  if (!id.determined) {
    out << "not determined: the velocities do not change over the run (a force-free run, or one at "
           "its terminal velocity), so the damping factor and gravity cannot be read from it; "
        << tied_fits(id) << " replay it equally well: this run cannot tell them apart (use a "
        << "scene whose velocities change)\n";
    return;
  }
  if (!id.fits_any) {
    out << "no member fits better than 2 cm: not a fixed-step scheme of the family (closest: "
        << law_key(best.law) << " at " << g3(best.max_dx) << " m)\n";
    return;
  }
  if (id.ambiguous) {
    out << "ambiguous: " << tied_fits(id) << " fit equally well: this scene cannot tell them apart"
        << hint(id) << "\n";
    return;
  }
  out << "best fit: " << law_key(best.law) << " (" << to_string(best.law) << ")"
      << printf_string(": residual %.3g m, phi = %.9g, ", best.max_dx, best.phi)
      << printf_string("g = (%.6g, %.6g, %.6g); runner-up ", best.gravity.x(), best.gravity.y(),
                       best.gravity.z())
      << law_key(next.law) << " at " << g3(next.max_dx) << " m\n";
}

// A rotational member and, when the scene's angular damping shows it, where the damping sits, or
// that it turns with the step-start angular velocity.
std::string rotation_member(const RotationFit& f, bool damping_seen) {
  // The semi-implicit member's key names the damping's place alone ("after-forces").
  if (damping_seen) return rotation_law_key(f.law) + ", " + law_key(f.linear);
  const bool explicit_turn = f.linear.position == PositionUpdate::Explicit;
  return rotation_law_key(f.law) + (explicit_turn ? ", step-start w" : "");
}

// The rotational fits, the verdict and, with an engine, its declared member.
void print_rotation(const RotationIdentification& id,
                    const std::optional<RotationDeclared>& declared, std::ostream& out) {
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
  }
  if (declared)
    out << "declared rotation " << rotation_member(declared->member, id.damping_seen) << ": "
        << match_word(declared->match) << "\n";
}

// The engine's observed order against the closed form, and whether it is its declared law's.
void print_order(const ClosedFormOrder& o, Law declared, bool matches, std::ostream& out) {
  if (!o.unavailable.empty()) {
    out << "order: not measured: " << o.unavailable << "\n";
    return;
  }
  out << "order against the closed form: " << o.estimate.text
      << (o.dropped.empty() ? "" : " (left out: " + o.dropped + ")") << "; declared "
      << law_key(declared) << " is order " << order_of(declared) << ": " << match_word(matches)
      << "\n";
}

// The law behind a free-flight run: the fits, the verdict, and what the engine declares.
void print_free_flight(const FreeFlightIdentity& f, std::ostream& out) {
  out << "identify " << f.scene << ": trajectory of " << f.engine << ", " << f.bodies << " bodies, "
      << f.steps << " steps"
      << " at h = " << sig(f.h, 9) << " s\n";
  print_fits(f.law, out);
  print_verdict(f.law, out);
  if (f.declared) {
    out << "declared " << law_key(*f.declared) << ": " << match_word(f.law_match) << "\n";
    print_order(*f.order, *f.declared, f.order_matches, out);
  }
  if (f.rotation)
    print_rotation(*f.rotation, f.rotation_declared, out);
  else if (f.rotation_unread)
    out << "rotation: the trajectory carries no rotation columns (qw..wz): its rotational law is "
           "not identified\n";
}

// An error-controlled engine is not fitted to a discrete member (law.hpp: it has none); its error
// against the closed form is printed per accuracy, each against its budget.
void print_accuracy_response(const AccuracyResponse& a, const EngineInfo& info, std::ostream& out) {
  out << "declared " << law_key(info.law) << " (" << to_string(info.law)
      << "): not fitted to a discrete member; its law is the continuous model, judged against "
         "the closed form within each accuracy's budget\n";
  if (!a.unavailable.empty()) {
    out << "error per accuracy: not measured: " << a.unavailable << "\n";
    return;
  }
  out << printf_string("  %-10s %16s %16s %14s %14s\n", "accuracy", "max|x - exact| m",
                       "max|v - exact|", "engine steps", "budget x m");
  for (const AccuracyPoint& p : a.points)
    out << printf_string("  %-10.3g %16.3g %16.3g %14lld %14.3g%s\n", p.accuracy, p.error_x,
                         p.error_v, static_cast<long long>(p.engine_steps), p.budget_x,
                         p.within() ? "" : "  OUTSIDE");
  out << "error per accuracy: "
      << (a.within() ? "within the budget at every accuracy" : "OUTSIDE the budget") << "\n";
}

// An engine's run on a free-flight scene: its error per accuracy, its failure or its law.
void print_engine(const EngineIdentity& e, std::ostream& out) {
  if (e.accuracy) {
    out << "identify " << e.scene << ": " << e.info.name << " at h = " << sig(e.h, 9) << " s\n";
    print_accuracy_response(*e.accuracy, e.info, out);
  } else if (e.failed) {
    out << "identify " << e.scene << ": " << failure_text(*e.failed) << "\n";
  } else {
    print_free_flight(*e.fit, out);
  }
}

// The friction model from the slides at 0 and 45 degrees, against the declared one.
void print_friction_model(const FrictionModelIdentity& f, std::ostream& out) {
  if (f.planar) {
    out << "friction model: not applicable: " << f.engine
        << " is a 2-D engine, with one tangent direction (a cone and the pyramids coincide)\n";
    return;
  }
  if (f.failed) {
    out << "identify " << f.scene << ": " << failure_text(*f.failed) << "\n";
    return;
  }
  if (!f.found) {
    out << "identify " << f.scene << ": " << f.engine << "'s slide at " << f.still_sliding_angle
        << " degrees still slides at the run's end ("
        << printf_string("%.7g m", f.still_sliding_distance) << "): no ratio; lengthen the scene\n";
    return;
  }
  out << "identify " << f.scene << ": " << f.engine << "'s friction from its slides at 0 and 45 "
      << "degrees"
      << (f.raw ? printf_string(" (each body's own coefficient: the pair's %.5g)", *f.mu)
                : std::string())
      << "\nfriction model: " << f.found->sentence() << "\n";
  if (f.raw)
    out << "declared: none (its adapter does not map friction)\n";
  else
    out << "declared " << to_string(f.declared) << ": "
        << (f.found->named || !f.ok() ? match_word(f.ok())
                                      : "consistent (this slide cannot tell it from another model)")
        << "\n";
}

void print_combine_rule(const CombineRuleIdentity& c, std::ostream& out) {
  if (c.per_pair)
    out << "combine rule: not identified: " << c.engine
        << "'s adapter sets each pair's friction itself (the engine has no per-body material)\n";
  else if (c.failed)
    out << "combine rule: " << failure_text(*c.failed) << "\n";
  else
    out << "combine rule: " << c.found->sentence() << "\n";
}

// An engine for identifying friction on `s`: the one `dropcheck check` would run, or, when its
// adapter does not map the scene's friction, the engine with each body's own coefficient passed
// verbatim (Engine::use_body_materials: its combine rule makes the pair's; `raw` says so). Throws
// InputError, with the reason, when neither can run the scene.
FrictionEngine friction_engine(const std::string& name, const Scene& s) {
  std::vector<SelectedEngine> engines = select_engines({name}, s);
  if (engines[0].engine) return {std::move(engines[0].engine), false};
  Scene plain = s;  // the scene as the engine would take it without the friction it cannot map
  for (Body& b : plain.bodies) b.friction.reset();
  std::unique_ptr<Engine> e = make_engine(name);
  if (!e || !e->cannot_run(plain).empty() || !e->use_body_materials())
    throw InputError("", 0, "--engine " + name, engines[0].skipped_because);
  return {std::move(e), true};
}

// The engine and steps of the request.
IdentifySource source_of(const IdentifyRequest& r) {
  return {[&r]() -> std::optional<EngineInfo> {
            const std::unique_ptr<Engine> e = make_engine(r.engine);
            if (!e) return std::nullopt;
            return e->info();
          },
          [&r](const Scene& s) { return friction_engine(r.engine, s); },
          [&r](const Scene& s) { return step_from_flag(r.dt, s).seconds; }};
}

void print_contact_law(const ContactLawIdentity& c, std::ostream& out) {
  if (c.failed) {
    out << "identify " << c.scene << ": " << failure_text(*c.failed) << "\n";
    return;
  }
  out << "identify " << c.scene << ": " << c.engine << "'s " << c.family
      << " from its run at h = " << printf_string("%.6g", c.h) << " s\n";
  for (const ContactMemberFit& f : c.fits) {
    std::string by;
    for (const std::string& e : f.declared_by) by += (by.empty() ? "" : ", ") + e;
    out << (!f.judged   ? "  untried  "
            : f.follows ? "  follows  "
                        : "  departs  ")
        << f.member << (by.empty() ? std::string() : " (declared by " + by + ")") << ": "
        << f.detail << "\n";
  }
  if (c.undeclared)
    out << "declared: none (its adapter declares no " << c.family
        << "; its landing is compared, not judged)\n";
  else
    out << "declared " << c.declared << ": " << match_word(c.ok()) << "\n";
}

// A slide: the contact solver the engine's run follows (harness/study/identify_contact.hpp), or
// why it is not identified (an engine that does not map the scene's friction).
int identify_solver(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  std::vector<SelectedEngine> engines = select_engines({r.engine}, scene);
  if (!engines[0].engine) {
    out << "contact solver: not identified: " << engines[0].skipped_because << "\n";
    return kExitOk;
  }
  const ContactLawIdentity c =
      identify_contact_solver(scene, *engines[0].engine, step_from_flag(r.dt, scene).seconds);
  print_contact_law(c, out);
  return c.ok() ? kExitOk : kExitCheckFailed;
}

// A slide to a stop: the engine's friction model (harness/oracles/identify_friction.hpp).
int identify_friction(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  if (r.engine.empty())
    throw InputError("", 0, "--trajectory",
                     "a slide is identified from two runs, at 0 and 45 degrees: use --engine E");
  const FrictionModelIdentity f = identify_friction_model(scene, source_of(r));
  print_friction_model(f, out);
  return std::max(f.ok() ? kExitOk : kExitCheckFailed, identify_solver(scene, r, out));
}

// The engine's combine rule for friction (harness/oracles/identify_friction.hpp): the slide with
// each body's coefficient passed verbatim. It runs outside the capability check on purpose: what
// is asked is the engine's own rule, which an adapter that maps the scene's value hides.
int identify_combine(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  std::unique_ptr<Engine> engine = make_engine(r.engine);
  if (!engine) throw InputError("", 0, "--engine " + r.engine, engine_unavailable_reason(r.engine));
  const CombineRuleIdentity c = identify_combine_rule(scene, *engine, source_of(r));
  print_combine_rule(c, out);
  return c.ok() ? kExitOk : kExitCheckFailed;
}

// A free-flight scene with --engine E: the engine's run at the scene's step (or --dt).
int identify_engine_law(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  std::vector<SelectedEngine> engines = select_engines({r.engine}, scene);
  if (!engines[0].engine)
    throw InputError("", 0, "--engine " + r.engine, engines[0].skipped_because);
  const double h = step_from_flag(r.dt, scene).seconds;
  const EngineIdentity e = identify_engine(scene, *engines[0].engine, h);
  print_engine(e, out);
  return e.ok() ? kExitOk : kExitCheckFailed;
}

// A free-flight scene with --trajectory CSV: the law behind the one run in the file.
int identify_trajectory(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  Trajectory run = trajectory_from_file(r.trajectory);
  adopt_scene_names(run, scene, out);
  const FreeFlightIdentity f = identify_free_flight(scene, run);
  print_free_flight(f, out);
  return f.ok() ? kExitOk : kExitCheckFailed;
}

// A bounce or a tumbling landing: the member of the contact law family the engine's run follows.
int identify_contact(const Scene& scene, const IdentifyRequest& r, std::ostream& out) {
  if (r.engine.empty())
    throw InputError("", 0, "--trajectory",
                     "a contact law is identified from an engine's run: use --engine E");
  std::vector<SelectedEngine> engines = select_engines({r.engine}, scene);
  if (!engines[0].engine)
    throw InputError("", 0, "--engine " + r.engine, engines[0].skipped_because);
  const double h = step_from_flag(r.dt, scene).seconds;
  const ContactLawIdentity c = bounce_setups(scene).empty()
                                   ? identify_turned_contact(scene, *engines[0].engine, h)
                                   : identify_bounce_law(scene, *engines[0].engine, h);
  print_contact_law(c, out);
  return c.ok() ? kExitOk : kExitCheckFailed;
}

int run_identify(const IdentifyRequest& r, std::ostream& out) {
  const Scene scene = load_scene(r.scene_file);
  if (r.combine && slide_setups(scene).empty())
    throw InputError(r.scene_file, 0, "--combine",
                     "applies to a slide launched along a level floor (docs/contact.md)");
  if (r.combine) {
    const int rule = identify_combine(scene, r, out);
    return std::max(rule, identify_friction(scene, r, out));
  }
  if (!slide_setups(scene).empty()) return identify_friction(scene, r, out);
  if (!bounce_setups(scene).empty() || (scene.world.contacts && needs_rotation(scene)))
    return identify_contact(scene, r, out);
  return r.engine.empty() ? identify_trajectory(scene, r, out) : identify_engine_law(scene, r, out);
}

}  // namespace

int cmd_identify(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  return run_identify(parse_identify_request(argv), out);
}

}  // namespace dropcheck
