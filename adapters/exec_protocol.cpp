#include "exec_protocol.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

// Longest free text (version, damping-mapping) kept from a handshake, in bytes: these reach the
// report's tables and the terminal.
constexpr std::size_t kMaxFreeText = 200;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

// The text after the first token ("error disk full" -> "disk full").
std::string rest_of(const std::string& line) {
  const std::size_t sp = line.find_first_of(" \t");
  if (sp == std::string::npos) return {};
  const std::size_t start = line.find_first_not_of(" \t", sp);
  return start == std::string::npos ? std::string() : line.substr(start);
}

// Free text an engine announced, as dropcheck keeps it: control bytes escaped (\xNN), then cut to
// at most kMaxFreeText bytes (never inside an escape or a UTF-8 character) with "..." after a cut.
std::string free_text(const std::string& text) {
  std::size_t take = std::min(text.size(), kMaxFreeText);
  std::string kept = escape_controls(text.substr(0, take));
  while (kept.size() > kMaxFreeText) {  // escapes grew it: give back input bytes until it fits
    take -= 1;
    while (take > 0 && (static_cast<unsigned char>(text[take]) & 0xc0) == 0x80) --take;
    kept = escape_controls(text.substr(0, take));
  }
  return take < text.size() ? kept + "..." : kept;
}

bool parse_number(const std::string& token, double& out) {
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, out);
  return ec == std::errc() && ptr == end;
}

bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.' &&
        c != '+')
      return false;
  return true;
}

[[noreturn]] void garbage(const std::string& expected, const std::string& got) {
  throw ProtocolError("garbage from the engine: expected " + expected + ", got " + excerpt(got));
}

// "bounce-law ERP MAX_PUSH velocity|position THRESHOLD DISTANCE DISTANCE_PER_SIZE
// [step-start|after-gravity approach|rebound MAX_REBOUND CFM overlap|touch]"
// (harness/core/bounce_law.hpp): ERP
// in [0, 1], MAX_PUSH and MAX_REBOUND > 0 or "inf", the rest finite and >= 0.
BounceLaw parse_bounce_law(const std::vector<std::string>& k, const std::string& line) {
  const char* form =
      "'bounce-law ERP MAX_PUSH velocity|position THRESHOLD DISTANCE DISTANCE_PER_SIZE "
      "[step-start|after-gravity approach|rebound MAX_REBOUND CFM overlap|touch]' (ERP in [0, 1], "
      "MAX_PUSH and "
      "MAX_REBOUND > 0 or inf, the others >= 0)";
  if ((k.size() != 7 && k.size() != 12) || (k[3] != "velocity" && k[3] != "position"))
    garbage(form, line);
  BounceLaw law;
  law.push_in_position = k[3] == "position";
  const auto number = [&](const std::string& text, double& out, bool may_be_infinite) {
    if (may_be_infinite && text == "inf") return;  // stays infinite
    if (!parse_number(text, out) || !std::isfinite(out) || out < 0.0) garbage(form, line);
  };
  number(k[1], law.erp, false);
  number(k[2], law.max_push, true);
  number(k[4], law.threshold, false);
  number(k[5], law.contact_distance, false);
  number(k[6], law.contact_distance_per_size, false);
  if (k.size() == 12) {
    if ((k[7] != "step-start" && k[7] != "after-gravity") ||
        (k[8] != "approach" && k[8] != "rebound") || (k[11] != "overlap" && k[11] != "touch"))
      garbage(form, line);
    law.touching = k[11] == "touch";
    law.free_approach = k[7] == "after-gravity";
    law.threshold_on_rebound = k[8] == "rebound";
    number(k[9], law.max_rebound, true);
    number(k[10], law.cfm, false);
  }
  if (law.erp > 1.0 || !(law.max_push > 0.0) || !(law.max_rebound > 0.0)) garbage(form, line);
  return law;
}

// "stack-law COMPLIANCE POINTS SOFT TAU_STEPS ITERATIONS SINK DRIFT STILL"
// (harness/core/stack_law.hpp): POINTS an integer >= 1, ITERATIONS an integer >= 0, the rest finite
// and >= 0.
StackLaw parse_stack_law(const std::vector<std::string>& k, const std::string& line) {
  const char* form =
      "'stack-law COMPLIANCE POINTS SOFT TAU_STEPS ITERATIONS SINK DRIFT STILL' (POINTS an "
      "integer 1-64, ITERATIONS an integer 0-1000000, the others finite and >= 0)";
  if (k.size() != 9) garbage(form, line);
  double v[8];
  for (std::size_t i = 0; i < 8; ++i)
    if (!parse_number(k[i + 1], v[i]) || !std::isfinite(v[i]) || v[i] < 0.0) garbage(form, line);
  if (v[1] < 1.0 || v[1] > 64.0 || v[1] != std::floor(v[1]) || v[4] > 1e6 ||
      v[4] != std::floor(v[4]))
    garbage(form, line);
  return {.compliance = v[0],
          .points = static_cast<int>(v[1]),
          .soft = v[2],
          .tau_steps = v[3],
          .iterations = static_cast<int>(v[4]),
          .sink_bound = v[5],
          .drift_bound = v[6],
          .still_bound = v[7]};
}

// "contact-solver exact", "contact-solver sequential-impulses ITERATIONS MEDIAN_BOUND" or
// "contact-solver soft MEDIAN_BOUND" (harness/core/contact_solver.hpp): ITERATIONS an integer
// 1-1000000, MEDIAN_BOUND in [0, 1].
ContactSolver parse_contact_solver(const std::vector<std::string>& k, const std::string& line) {
  const char* form =
      "'contact-solver exact', 'contact-solver sequential-impulses ITERATIONS MEDIAN_BOUND' or "
      "'contact-solver soft MEDIAN_BOUND' (ITERATIONS an integer 1-1000000, MEDIAN_BOUND in [0, "
      "1])";
  if (k.size() == 2 && k[1] == "exact") return {};
  const auto bound = [&](const std::string& text) {
    double b = 0.0;
    if (!parse_number(text, b) || !(b >= 0.0 && b <= 1.0)) garbage(form, line);
    return b;
  };
  if (k.size() == 4 && k[1] == "sequential-impulses") {
    double n = 0.0;
    if (!parse_number(k[2], n) || !(n >= 1.0 && n <= 1e6) || n != std::floor(n))
      garbage(form, line);
    return {.kind = ContactSolverKind::sequential_impulses,
            .velocity_iterations = static_cast<int>(n),
            .coulomb_median_bound = bound(k[3])};
  }
  if (k.size() == 3 && k[1] == "soft")
    return {.kind = ContactSolverKind::soft, .coulomb_median_bound = bound(k[2])};
  garbage(form, line);
}

}  // namespace

std::string engine_name_problem(const std::string& name, const std::vector<std::string>& reserved) {
  if (!valid_name(name))
    return excerpt(name) + " is not a valid engine name (1-64 of A-Z a-z 0-9 . _ + -)";
  for (const std::string& builtin : reserved)
    if (name == builtin) return "'" + name + "' is the name of a built-in engine; choose another";
  return {};
}

bool HandshakeReader::take(const std::string& line) {
  if (++lines_ > kMaxHandshakeLines)
    throw ProtocolError("garbage from the engine: a handshake of more than " +
                        std::to_string(kMaxHandshakeLines) + " lines without 'ready'");
  const std::vector<std::string> t = split(line);
  if (!started_) {
    first(t, line);
    started_ = true;
    return false;
  }
  if (t.size() == 1 && t[0] == "ready") {
    if (!name_ || !version_ || !scalar_ || !law_)
      throw ProtocolError("the handshake lacks " + std::string(!name_      ? "name"
                                                               : !version_ ? "version"
                                                               : !scalar_  ? "scalar"
                                                                           : "law"));
    const Capabilities& c = info_.capabilities;
    if ((c.friction || c.restitution || c.spheres) && !c.contacts)
      throw ProtocolError(
          "the handshake announces friction, restitution or spheres without 'contacts'");
    if (info_.capabilities.rotation != Rotation::none && !rotation_law_)
      throw ProtocolError(
          "the handshake announces rotation but lacks 'rotation-law KEY' (the engine's "
          "rotational member)");
    return true;
  }
  if (t.empty()) garbage("a handshake line", line);
  key(t, line);
  return false;
}

void HandshakeReader::first(const std::vector<std::string>& t, const std::string& line) {
  if (t.size() != 2 || t[0] != "dropcheck-engine") garbage("'dropcheck-engine 1'", line);
  if (t[1] != std::to_string(kProtocolVersion))
    throw ProtocolError("the engine speaks protocol " + excerpt(t[1]) + "; dropcheck speaks " +
                        std::to_string(kProtocolVersion));
}

void HandshakeReader::key(const std::vector<std::string>& k, const std::string& line) {
  const std::string value = rest_of(line);
  if (k[0] == "name" && k.size() == 2) {
    if (!keep_name_) {
      if (std::string p = engine_name_problem(k[1], reserved_); !p.empty()) throw ProtocolError(p);
      info_.name = k[1];
    }
    name_ = true;
  } else if (k[0] == "version" && k.size() >= 2) {
    info_.version = free_text(value);
    version_ = true;
  } else if (k[0] == "scalar" && k.size() == 2 && (k[1] == "f32" || k[1] == "f64")) {
    info_.scalar = k[1] == "f32" ? Scalar::f32 : Scalar::f64;
    scalar_ = true;
  } else if (k[0] == "law" && k.size() == 2 && parse_law_key(k[1])) {
    info_.law = *parse_law_key(k[1]);
    law_ = true;
  } else if (k[0] == "capabilities") {
    for (std::size_t i = 1; i < k.size(); ++i) {
      if (k[i] == "contacts")
        info_.capabilities.contacts = true;
      else if (k[i] == "planar-only")
        info_.capabilities.planar_only = true;
      else if (k[i] == "continuous-collision")
        info_.continuous_collision = true;
      else if (k[i] == "rotation")
        info_.capabilities.rotation = Rotation::full;
      else if (k[i] == "rotation-z")
        info_.capabilities.rotation = Rotation::spin_z;
      else if (k[i] == "friction")
        info_.capabilities.friction = true;
      else if (k[i] == "restitution")
        info_.capabilities.restitution = true;
      else if (k[i] == "spheres")
        info_.capabilities.spheres = true;
      else
        garbage(
            "capabilities 'contacts', 'planar-only', 'continuous-collision', 'rotation', "
            "'rotation-z', 'friction', 'restitution' or 'spheres'",
            line);
    }
  } else if (k[0] == "friction-model" && k.size() == 2 &&
             parse_friction_model_key(k[1], info_.friction_model)) {
  } else if (k[0] == "bounce-law") {
    info_.bounce_law = parse_bounce_law(k, line);
  } else if (k[0] == "stack-law") {
    info_.stack_law = parse_stack_law(k, line);
  } else if (k[0] == "contact-solver") {
    info_.contact_solver = parse_contact_solver(k, line);
  } else if (k[0] == "rotation-law" && k.size() == 2 && parse_rotation_law_key(k[1])) {
    info_.rotation_law = *parse_rotation_law_key(k[1]);
    rotation_law_ = true;
  } else if (k[0] == "damping-mapping" && k.size() >= 2) {
    info_.damping_mapping = free_text(value);
  } else {
    garbage(
        "name, version, scalar f32|f64, law KEY, capabilities, rotation-law KEY, "
        "friction-model cone|box-pyramid|sum-pyramid, bounce-law, stack-law, contact-solver, "
        "damping-mapping or "
        "ready "
        "(law keys: after-forces, before-forces, after-position, "
        "after-forces/explicit, before-forces/explicit; rotation-law keys: "
        "GYRO/UPDATE with GYRO no-gyro, explicit, implicit-body, linearly-implicit and UPDATE "
        "first-order, exp-map)",
        line);
  }
}

namespace {

// "state N" and `per_body` numbers per body, checked and parsed; `put(i, v)` stores number i.
template <typename Put>
void parse_numbers(const std::string& line, std::int64_t n, std::size_t bodies,
                   std::size_t per_body, Put&& put) {
  const std::vector<std::string> t = split(line);
  const std::string head = "'state " + std::to_string(n) + "'";
  const std::size_t want = per_body * bodies;
  if (t.size() < 2 || t[0] != "state" || t[1] != std::to_string(n))
    garbage(head + " and " + std::to_string(want) + " numbers", line);
  const std::size_t got = t.size() - 2;
  if (got != want) {
    const std::string per =
        got % per_body == 0 ? " (" + std::to_string(got / per_body) + " bodies)" : "";
    throw ProtocolError("the engine answered " + std::to_string(got) + " numbers" + per +
                        ", the scene has " + std::to_string(bodies) + " bodies (" +
                        std::to_string(want) + " numbers" +
                        (per_body == 13 ? ": 13 per body in a rotating scene" : "") + ")");
  }
  for (std::size_t i = 0; i < got; ++i) {
    double v = 0.0;
    if (!parse_number(t[2 + i], v)) garbage("a number", t[2 + i]);
    put(i, v);
  }
}

}  // namespace

void parse_state_line(const std::string& line, std::int64_t n, std::span<BodyState> out) {
  parse_numbers(line, n, out.size(), 6, [&](std::size_t i, double v) {
    BodyState& s = out[i / 6];
    (i % 6 < 3 ? s.position : s.velocity)[static_cast<Eigen::Index>(i % 3)] = v;
  });
}

void parse_state_line(const std::string& line, std::int64_t n, std::span<BodyState> out,
                      std::span<RotationState> turns) {
  parse_numbers(line, n, out.size(), 13, [&](std::size_t i, double v) {
    const std::size_t b = i / 13, k = i % 13;
    if (k < 3)
      out[b].position[static_cast<Eigen::Index>(k)] = v;
    else if (k < 6)
      out[b].velocity[static_cast<Eigen::Index>(k - 3)] = v;
    else if (k == 6)
      turns[b].orientation.w() = v;
    else if (k < 10)
      turns[b].orientation.vec()[static_cast<Eigen::Index>(k - 7)] = v;
    else
      turns[b].angular_velocity[static_cast<Eigen::Index>(k - 10)] = v;
  });
}

bool is_error_line(const std::string& line) {
  return line.rfind("error", 0) == 0 && (line.size() == 5 || line[5] == ' ' || line[5] == '\t');
}

std::string error_text(const std::string& line) {
  return is_error_line(line) ? free_text(rest_of(line)) : std::string();
}

}  // namespace dropcheck
