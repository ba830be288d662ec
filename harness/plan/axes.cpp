#include "harness/plan/axes.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <vector>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/scene/toml_reader.hpp"

namespace dropcheck {
namespace {

struct Segment {
  std::string name;
  std::optional<std::size_t> index;
};

// "body[0]" -> {body, 0}; "mass" -> {mass}.
std::vector<Segment> split_path(const std::string& path) {
  std::vector<Segment> out;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    std::string part =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    Segment s;
    if (const std::size_t open = part.find('['); open != std::string::npos) {
      if (part.back() != ']' || open + 2 > part.size() - 1)
        throw InputError("key " + excerpt(path) + ": bad index in " + excerpt(part));
      const std::string digits = part.substr(open + 1, part.size() - open - 2);
      if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6)
        throw InputError("key " + excerpt(path) + ": bad index in " + excerpt(part));
      s.index = std::stoul(digits);
      part.resize(open);
    }
    if (part.empty()) throw InputError("key " + excerpt(path) + ": an empty name in the path");
    s.name = part;
    out.push_back(s);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return out;
}

// The element of an array of tables whose `name` is `name`.
toml::table* named_table(toml::array& a, const std::string& name) {
  for (toml::node& n : a)
    if (toml::table* t = n.as_table();
        t && t->get("name") && t->get("name")->value<std::string>() == name)
      return t;
  return nullptr;
}

void set_key(toml::table& root, const std::string& path, double value) {
  const std::vector<Segment> segments = split_path(path);
  const auto fail = [&](const std::string& why) {
    throw InputError("key " + excerpt(path) + ": " + why);
  };
  toml::table* table = &root;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    const bool last = i + 1 == segments.size();
    if (last && !s.index) {
      const toml::node* old = table->get(s.name);
      if (old && !old->is_number()) fail(s.name + " is not a number");
      table->insert_or_assign(s.name, value);
      return;
    }
    toml::node* n = table->get(s.name);
    if (!n) fail("no " + excerpt(s.name) + " in the scene");
    if (toml::table* t = n->as_table(); t && !s.index) {
      table = t;
      continue;
    }
    toml::array* a = n->as_array();
    if (!a) fail(s.name + " is neither a table nor an array");
    if (s.index) {
      if (*s.index >= a->size()) fail(s.name + " has no element " + std::to_string(*s.index));
      toml::node& e = *a->get(*s.index);
      if (last) {
        if (!e.is_number()) fail(s.name + "[" + std::to_string(*s.index) + "] is not a number");
        a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(*s.index), value);
        return;
      }
      if (!e.as_table()) fail(s.name + "[" + std::to_string(*s.index) + "] is not a table");
      table = e.as_table();
      continue;
    }
    // [[body]] by name: the next segment names the table.
    if (last || !a->is_array_of_tables()) fail(s.name + " needs an [index]");
    toml::table* t = named_table(*a, segments[i + 1].name);
    if (!t) fail("no " + s.name + " named " + excerpt(segments[i + 1].name));
    table = t;
    ++i;
    if (segments[i].index) fail("a name selects one table: no index after " + segments[i].name);
  }
  fail("the path ends on a table, not a number");
}

// An axis value as a number: the whole text, finite (a plan is data: "abc", "1e999" are refused).
double number_of(const std::string& axis, const std::string& text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(axis + ": " + excerpt(text) + " is not a finite number");
  return v;
}

double magnitude(const Axis& a, const std::string& value) {
  const double v = number_of(a.name, value);
  if (!(v >= 0.0)) throw InputError(std::string(to_string(a.kind)) + " must be >= 0, got " + value);
  return v;
}

void apply_named(const Axis& a, const std::string& value, CellSetup& c) {
  Scene& s = c.scene;
  switch (a.kind) {
    case AxisKind::timestep: {
      std::string why;
      const std::optional<Timestep> h = parse_timestep(value, why);
      if (!h) throw InputError("timestep " + value + ": " + why);
      c.h = *h;
      return;
    }
    case AxisKind::damping_rate:
      s.world.damping_rate = magnitude(a, value);
      return;
    case AxisKind::gravity: {
      const double g = s.world.gravity.norm();
      const Vec3 dir = g > 0.0 ? Vec3(s.world.gravity / g) : Vec3(0.0, -1.0, 0.0);
      s.world.gravity = magnitude(a, value) * dir;
      return;
    }
    case AxisKind::spring_stiffness: {
      bool any = false;
      for (Force& f : s.forces)
        if (Spring* sp = std::get_if<Spring>(&f.law))
          sp->stiffness = magnitude(a, value), any = true;
      if (!any) throw InputError("spring_stiffness: scene " + s.name + " has no spring");
      return;
    }
    case AxisKind::mass_ratio: {
      const double ratio = magnitude(a, value);
      if (ratio == 0.0) throw InputError("mass_ratio must be > 0");
      std::optional<double> first;
      int others = 0;
      for (Body& b : s.bodies) {
        if (b.is_static) continue;
        if (!first)
          first = b.mass;
        else
          b.mass = ratio * *first, ++others;
      }
      if (others == 0)
        throw InputError("mass_ratio: scene " + s.name + " has fewer than two dynamic bodies");
      return;
    }
    case AxisKind::initial_speed: {
      const double speed = magnitude(a, value);
      for (Body& b : s.bodies) {
        if (b.is_static) continue;
        const double v = b.velocity.norm();
        b.velocity = speed * (v > 0.0 ? Vec3(b.velocity / v) : Vec3(0.0, 1.0, 0.0));
      }
      return;
    }
    case AxisKind::scalar:
      if (value != "f32" && value != "f64")
        throw InputError("scalar: " + excerpt(value) + " is neither f32 nor f64");
      c.scalar = value;
      if (c.engine == "ours" || c.engine == "ours-f64")
        c.engine = value == "f32" ? "ours" : "ours-f64";
      return;
    case AxisKind::scene_key:
      return;  // applied to the TOML
  }
}

}  // namespace

void check_canonical_value(const Axis& axis, const std::string& text) {
  if (axis.kind == AxisKind::scalar) {
    if (text != "f32" && text != "f64")
      throw InputError(axis.name + ": " + excerpt(text) + " is neither f32 nor f64");
    return;
  }
  if (axis.kind == AxisKind::timestep) {
    std::string why;
    const std::optional<Timestep> h = parse_timestep(text, why);
    if (!h || h->text != text) throw InputError("timestep: " + excerpt(text) + " is not a step");
    return;
  }
  if (shortest(number_of(axis.name, text)) != text)
    throw InputError(axis.name + ": " + excerpt(text) + " is not written as the shortest number");
}

CellSetup setup_cell(const std::string& text, const std::string& file, const std::string& engine,
                     std::span<const Axis> axes, std::span<const std::string> values) {
  toml::table root = parse_toml(text, file);
  for (std::size_t i = 0; i < axes.size(); ++i)
    if (axes[i].kind == AxisKind::scene_key)
      set_key(root, axes[i].name, number_of(axes[i].name, values[i]));
  CellSetup c{scene_from_table(root, text, file), {}, engine, ""};
  c.h = c.scene.timestep;
  for (std::size_t i = 0; i < axes.size(); ++i) apply_named(axes[i], values[i], c);
  return c;
}

}  // namespace dropcheck
