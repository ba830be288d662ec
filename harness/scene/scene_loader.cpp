#include "harness/scene/scene_loader.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/rotation_law.hpp"
#include "harness/core/timestep.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/scene/expect_table.hpp"
#include "harness/scene/toml_ascii.hpp"
#include "harness/scene/toml_reader.hpp"

namespace dropcheck {
namespace {

void check_range(const Reader& r, const std::string& key, bool ok, const std::string& rule) {
  if (!ok) r.fail(key, rule + ", got " + Reader::format(r.number(key, 0.0)));
}

void load_times(const Reader& r, Scene& s) {
  s.duration = r.required_number("duration");
  check_range(r, "duration", s.duration > 0.0, "must be > 0 seconds");
  if (r.has("timestep")) s.timestep = r.timestep("timestep", *r.node("timestep"));
  if (std::string why = step_problem(s.duration, s.timestep.seconds); !why.empty())
    r.fail("timestep", why);
  if (const toml::node* n = r.node("timesteps")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) r.fail("timesteps", "expected a non-empty array of steps", n);
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string key = "timesteps[" + std::to_string(i) + "]";
      Timestep t = r.timestep(key, *a->get(i));
      if (std::string why = step_problem(s.duration, t.seconds); !why.empty())
        r.fail(key, why, a->get(i));
      s.timesteps.push_back(t);
    }
  } else {
    s.timesteps.push_back(s.timestep);
  }
  s.tolerance = r.number("tolerance", s.tolerance);
  check_range(r, "tolerance", s.tolerance > 0.0, "must be > 0 m");
}

// linear_drag f is the seed's per-step factor at `timestep`: k = -ln(f)/h, so exp(-k*h) = f.
// The same for a damping rate given as `drag_key` (the seed's factor) or `rate_key` (k itself).
double damping_rate(const Reader& r, const std::string& drag_key, const std::string& rate_key,
                    const Scene& s) {
  if (r.has(drag_key) && r.has(rate_key))
    r.fail(rate_key, "give " + drag_key + " or " + rate_key + ", not both");
  if (r.has(drag_key)) {
    const double f = r.number(drag_key, 1.0);
    check_range(r, drag_key, f > 0.0 && f <= 1.0, "must be in (0, 1]");
    return -std::log(f) / s.timestep.seconds;
  }
  const double k = r.number(rate_key, 0.0);
  check_range(r, rate_key, k >= 0.0, "must be >= 0 (1/s)");
  return k;
}

void load_world(const Reader& top, Scene& s) {
  const toml::node* n = top.node("world");
  if (!n) top.fail("world", "required table [world] is missing");
  if (!n->is_table()) top.fail("world", "expected a table [world]", n);
  Reader r(top.file(), *n->as_table(), "world");
  r.only(
      {"gravity", "linear_drag", "linear_damping", "angular_drag", "angular_damping", "contacts"});
  s.world.gravity = r.vec3("gravity", Vec3::Zero(), true);
  s.world.damping_rate = damping_rate(r, "linear_drag", "linear_damping", s);
  s.world.angular_damping_rate = damping_rate(r, "angular_drag", "angular_damping", s);
  s.world.contacts = r.boolean("contacts", false);
}

// How far a given orientation's norm may be from 1: rounding of 17 significant digits per
// component, with room to spare (a quaternion typed to 4 digits, 0.7071, is 2e-5 off: refused).
constexpr double kUnitTolerance = 1e-12;

// orientation = [w, x, y, z] (unit), angular_velocity = [x, y, z] (rad/s, world frame), inertia =
// [Ixx, Iyy, Izz] (principal moments in the body frame; default: a uniform box).
void load_rotation(const Reader& r, Body& b) {
  if (const toml::node* n = r.node("orientation")) {
    const toml::array* a = n->as_array();
    if (!a || a->size() != 4) r.fail("orientation", "expected a unit quaternion [w, x, y, z]", n);
    double q[4];
    for (std::size_t i = 0; i < 4; ++i)
      q[i] = r.number("orientation[" + std::to_string(i) + "]", *a->get(i));
    b.orientation = Quat(q[0], q[1], q[2], q[3]);
    const double norm = b.orientation.norm();
    if (!(std::abs(norm - 1.0) <= kUnitTolerance))
      r.fail("orientation", "not a unit quaternion: its norm is " + shortest(norm) +
                                " (1 within 1e-12 expected; give every component to 17 digits)");
    b.orientation.normalize();
  }
  b.angular_velocity = r.vec3("angular_velocity", Vec3::Zero());
  b.inertia = b.shape == Shape::sphere ? sphere_inertia(b.mass, b.radius)
                                       : box_inertia(b.mass, b.half_extents);
  if (r.has("inertia")) {
    b.inertia = r.vec3("inertia", b.inertia);
    if (!(b.inertia.array() > 0.0).all())
      r.fail("inertia", "every principal moment must be > 0 kg m^2");
    const char* axes[] = {"Ixx", "Iyy", "Izz"};
    for (int i = 0; i < 3; ++i) {
      const double others = b.inertia[(i + 1) % 3] + b.inertia[(i + 2) % 3];
      if (b.inertia[i] > others * (1.0 + kUnitTolerance))  // equality: a flat plate
        r.fail("inertia", std::string(axes[i]) + " = " + shortest(b.inertia[i]) +
                              " exceeds the sum of the other two (" + shortest(others) +
                              "): no body has these moments (triangle inequality)");
    }
  }
}

// shape = "box" (default: half_extents) or "sphere" (radius, required; no half_extents).
void load_shape(const Reader& r, Body& b) {
  const std::string shape = r.string("shape", "box");
  if (shape != "box" && shape != "sphere")
    r.fail("shape", "expected \"box\" or \"sphere\", got " + excerpt(shape));
  if (shape == "box") {
    if (r.has("radius"))
      r.fail("radius", "a box has half_extents; radius is for shape = \"sphere\"");
    b.half_extents = r.vec3("half_extents", b.half_extents);
    if (!(b.half_extents.array() > 0.0).all())
      r.fail("half_extents", "every half extent must be > 0 m");
    return;
  }
  if (r.has("half_extents"))
    r.fail("half_extents", "a sphere has a radius; half_extents are for shape = \"box\"");
  b.shape = Shape::sphere;
  b.radius = r.required_number("radius");
  check_range(r, "radius", b.radius > 0.0, "must be > 0 m");
  b.half_extents = Vec3::Constant(b.radius);
}

// friction = mu (>= 0) and restitution = e (0..1): the body's contact material (docs/contact.md).
// One value per scene: every contact of the scene uses it, so that no engine's combine rule (a
// product, a mean, the larger) decides what two bodies' values make.
void load_material(const Reader& r, Body& b, const Scene& s) {
  if (r.has("friction")) {
    b.friction = r.number("friction", 0.0);
    check_range(r, "friction", *b.friction >= 0.0, "must be >= 0 (a Coulomb coefficient)");
  }
  if (r.has("restitution")) {
    b.restitution = r.number("restitution", 0.0);
    check_range(r, "restitution", *b.restitution >= 0.0 && *b.restitution <= 1.0,
                "must be in [0, 1]");
  }
  for (const Body& other : s.bodies) {
    if (b.friction && other.friction && *b.friction != *other.friction)
      r.fail("friction", "one friction per scene (docs/contact.md): body \"" + other.name +
                             "\" sets " + shortest(*other.friction));
    if (b.restitution && other.restitution && *b.restitution != *other.restitution)
      r.fail("restitution", "one restitution per scene (docs/contact.md): body \"" + other.name +
                                "\" sets " + shortest(*other.restitution));
  }
}

void load_body(const Reader& r, Scene& s) {
  r.only({"name", "shape", "radius", "half_extents", "mass", "position", "velocity", "static",
          "orientation", "angular_velocity", "inertia", "friction", "restitution"});
  Body b;
  if (!r.has("name")) r.fail("name", "required key is missing");
  b.name = r.name("name", "");
  if (b.name.empty()) r.fail("name", "must not be empty");
  for (const Body& other : s.bodies)
    if (other.name == b.name) r.fail("name", "duplicate body name \"" + b.name + "\"");
  load_shape(r, b);
  load_material(r, b, s);
  b.mass = r.number("mass", b.mass);
  check_range(r, "mass", b.mass > 0.0, "must be > 0 kg");
  b.position = r.vec3("position", Vec3::Zero(), true);
  b.velocity = r.vec3("velocity", Vec3::Zero());
  b.is_static = r.boolean("static", false);
  load_rotation(r, b);
  // A static body neither turns nor stands turned: engines place static geometry axis-aligned
  // (ODE, MuJoCo and Box2D would ignore a turn that Bullet applies, and collide differently).
  for (const char* key : {"orientation", "angular_velocity"})
    if (b.is_static && r.has(key))
      r.fail(key,
             "a static body does not turn: give orientation and angular_velocity to "
             "dynamic bodies only");
  s.bodies.push_back(b);
}

std::size_t body_index(const Reader& r, const Scene& s, const std::string& key,
                       const std::string& name) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies[i].name != name) continue;
    if (s.bodies[i].is_static)
      r.fail(key, "body \"" + name + "\" is static; forces act on dynamic bodies");
    return i;
  }
  r.fail(key, "no body named " + excerpt(name));
}

Spring load_spring(const Reader& parent, const toml::node& n) {
  if (!n.is_table())
    parent.fail("spring", "expected an inline table { anchor = [...], stiffness = ... }", &n);
  Reader r(parent.file(), *n.as_table(), parent.path("spring"));
  r.only({"anchor", "stiffness", "damping", "rest_length"});
  Spring sp;
  sp.anchor = r.vec3("anchor", Vec3::Zero(), true);
  sp.stiffness = r.required_number("stiffness");
  check_range(r, "stiffness", sp.stiffness >= 0.0, "must be >= 0 N/m");
  sp.damping = r.number("damping", 0.0);
  check_range(r, "damping", sp.damping >= 0.0, "must be >= 0 N*s/m");
  sp.rest_length = r.number("rest_length", 0.0);
  check_range(r, "rest_length", sp.rest_length >= 0.0, "must be >= 0 m");
  return sp;
}

// `bodies = [names]` of a [[force]] or [[torque]] (`what`), or every dynamic body when absent.
std::vector<std::size_t> acted_on(const Reader& r, const Scene& s, const std::string& what) {
  std::vector<std::size_t> out;
  if (const toml::node* n = r.node("bodies")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) r.fail("bodies", "expected a non-empty array of body names", n);
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string key = "bodies[" + std::to_string(i) + "]";
      if (!a->get(i)->is_string()) r.fail(key, "expected a body name (string)", a->get(i));
      const std::size_t b = body_index(r, s, key, *a->get(i)->value<std::string>());
      if (std::find(out.begin(), out.end(), b) != out.end())
        r.fail(key,
               "body \"" + s.bodies[b].name + "\" is listed twice; the " + what +
                   " would act on it twice",
               a->get(i));
      out.push_back(b);
    }
  } else {
    for (std::size_t i = 0; i < s.bodies.size(); ++i)
      if (!s.bodies[i].is_static) out.push_back(i);
  }
  return out;
}

// [[torque]]: constant = [x, y, z] (N m, world frame) on the bodies listed (default: all dynamic).
void load_torque(const Reader& r, Scene& s) {
  r.only({"bodies", "constant"});
  Torque t;
  t.bodies = acted_on(r, s, "torque");
  t.torque = r.vec3("constant", Vec3::Zero(), true);
  s.torques.push_back(t);
}

void load_force(const Reader& r, Scene& s) {
  r.only({"bodies", "constant", "spring"});
  Force f;
  f.bodies = acted_on(r, s, "force");
  if (r.has("constant") == r.has("spring"))
    r.fail("constant", "give exactly one of constant or spring");
  if (r.has("constant"))
    f.law = ConstantForce{r.vec3("constant", Vec3::Zero())};
  else
    f.law = load_spring(r, *r.node("spring"));
  s.forces.push_back(f);
}

// Steps the report replays a published figure's member for (4.3e8 bytes of states at most).
constexpr double kMaxPublishedSteps = 1e7;

// [[published]]: a figure published for this scene and the rotational member that predicts it.
void load_published(const Reader& r, Scene& s) {
  r.only({"source", "engine", "dt", "max_momentum_drift", "law", "law_dt", "note"});
  PublishedFigure p;
  p.source = r.name("source", "");
  p.engine = r.name("engine", "");
  if (p.source.empty() || p.engine.empty()) r.fail("source", "source and engine are required");
  p.dt = r.required_number("dt");
  check_range(r, "dt", p.dt > 0.0, "must be > 0 (s)");
  p.max_momentum_drift = r.required_number("max_momentum_drift");
  check_range(r, "max_momentum_drift", p.max_momentum_drift >= 0.0, "must be >= 0");
  p.law = r.string("law", "");
  if (!parse_rotation_law_key(p.law)) {
    std::string keys;
    for (RotationLaw law : kRotationFamily)
      keys += (keys.empty() ? "" : ", ") + rotation_law_key(law);
    r.fail("law", "expected a rotational member: one of " + keys);
  }
  p.law_dt = r.number("law_dt", p.dt);
  // The member is replayed step by step at law_dt over the scene: at least one step, at most
  // kMaxPublishedSteps (the report holds every step of it).
  const double steps = s.duration / p.law_dt;
  check_range(r, "law_dt", p.law_dt > 0.0 && steps >= 1.0 && steps <= kMaxPublishedSteps,
              "must be > 0 s, at most the scene's duration, and leave at most 1e7 steps");
  p.note = r.name("note", "");
  if (!needs_rotation(s)) r.fail("law", "published rotation figures need a scene that rotates");
  s.published.push_back(p);
}

Scene build(const toml::table& root, const std::string& text, const std::string& path) {
  Reader r(path, root, "");
  r.only({"name", "description", "duration", "timestep", "timesteps", "tolerance", "world", "body",
          "force", "torque", "published", "expect"});
  Scene s;
  s.source = path;
  s.name = r.name("name", std::filesystem::path(path).stem().string());
  s.description = r.string("description", "");
  load_times(r, s);
  load_world(r, s);
  const toml::array* bodies = array_of_tables(r, "body");
  if (!bodies || bodies->empty()) r.fail("body", "a scene needs at least one [[body]]");
  for (std::size_t i = 0; i < bodies->size(); ++i)
    load_body(Reader(path, *bodies->get(i)->as_table(), "body[" + std::to_string(i) + "]"), s);
  if (const toml::array* forces = array_of_tables(r, "force"))
    for (std::size_t i = 0; i < forces->size(); ++i)
      load_force(Reader(path, *forces->get(i)->as_table(), "force[" + std::to_string(i) + "]"), s);
  if (const toml::array* torques = array_of_tables(r, "torque"))
    for (std::size_t i = 0; i < torques->size(); ++i)
      load_torque(Reader(path, *torques->get(i)->as_table(), "torque[" + std::to_string(i) + "]"),
                  s);
  if (const toml::array* published = array_of_tables(r, "published"))
    for (std::size_t i = 0; i < published->size(); ++i)
      load_published(
          Reader(path, *published->get(i)->as_table(), "published[" + std::to_string(i) + "]"), s);
  load_expect(r, text, s);  // after the bodies: a table in [expect] names one
  return s;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& path) {
  return build(parse_toml(text, path), text, path);
}

Scene scene_from_table(const toml::table& root, const std::string& text, const std::string& path) {
  return build(root, text, path);
}

Scene load_scene(const std::string& path) {
  return parse_scene(read_scene_text(path), path);
}

std::string read_scene_text(const std::string& path) {
  return read_regular_file(path, kMaxSceneBytes, "1 MiB, for a scene");
}

}  // namespace dropcheck
