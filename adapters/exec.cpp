// Adapter for external engines: a child process speaking docs/protocol.md over stdin/stdout.
//
// Mapping (scene -> protocol): the scene is sent once per load() ("scene" ... "end": h, gravity,
// damping rate k with phi = exp(-k*h), contacts flag, one "body" line per body); each step sends
// the harness's forces and reads back every body's position and velocity. Numbers go out with %.17g
// and come back through std::from_chars, so nothing is lost at the boundary. Every failure of the
// engine (cannot start, crash, hang, garbage, wrong body count, early exit, "error TEXT") is an
// EngineError naming the step; the child is then killed and reaped.
#include "exec.hpp"

#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <filesystem>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/process/child_process.hpp"

namespace dropcheck {
namespace {

constexpr int kProtocolVersion = 1;

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

// A line quoted for an error message: at most 80 characters, control bytes shown as '?'.
std::string quote(const std::string& line) {
  std::string q = line.substr(0, 80);
  for (char& c : q)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f) c = '?';
  return "'" + q + (line.size() > 80 ? "...'" : "'");
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

// Why `name` cannot name an external engine; empty when it can.
std::string name_problem(const std::string& name) {
  if (!valid_name(name))
    return "'" + name + "' is not a valid engine name (1-64 of A-Z a-z 0-9 . _ + -)";
  for (const std::string& builtin : known_engine_names())
    if (name == builtin) return "'" + name + "' is the name of a built-in engine; choose another";
  return {};
}

std::string format_seconds(double s) {
  return sig(s, 6) + " s";
}

class ExecEngine final : public Engine {
 public:
  explicit ExecEngine(ExecSpec spec) : spec_(std::move(spec)) {
    info_.name =
        spec_.name.empty() ? std::filesystem::path(spec_.command[0]).stem().string() : spec_.name;
    info_.version = "?";
    info_.damping_mapping = "the engine's own (external, docs/protocol.md)";
    try {
      child_ = std::make_unique<ChildProcess>(spec_.command, spec_.cwd);
      handshake();
    } catch (const EngineError&) {
      // failure_ is set: load() reports it as the run's result.
    } catch (const std::exception& e) {
      failure_ = std::string("at start: ") + e.what();
    }
  }

  ~ExecEngine() override {
    if (child_ && failure_.empty()) child_->write_line("quit", 0.2);
  }

  EngineInfo info() const override { return info_; }

  void load(const Scene& scene, double h) override {
    if (!failure_.empty()) throw EngineError(failure_);
    const std::size_t n = scene.bodies.size();
    states_.assign(n, {});
    forces_.assign(n, Vec3::Zero());
    step_ = 0;
    where_ = "at load";
    send("scene " + std::to_string(n));
    send("h " + exact(h));
    const Vec3& g = scene.world.gravity;
    send("gravity " + exact(g.x()) + " " + exact(g.y()) + " " + exact(g.z()));
    send("damping " + exact(scene.world.damping_rate) + " " + exact(decay_per_step(scene, h)));
    send(std::string("contacts ") + (scene.world.contacts ? "1" : "0"));
    for (const Body& b : scene.bodies) send(body_line(b));
    send("end");
    read_state(0);
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < forces_.size() && i < forces.size(); ++i) forces_[i] = forces[i];
  }

  void step() override {
    if (!failure_.empty()) throw EngineError(failure_);
    ++step_;
    where_ = "at step " + std::to_string(step_);
    std::string line = "step " + std::to_string(step_);
    for (const Vec3& f : forces_)
      line += " " + exact(f.x()) + " " + exact(f.y()) + " " + exact(f.z());
    send(line);
    read_state(step_);
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < states_.size() && i < out.size(); ++i) out[i] = states_[i];
  }

 private:
  static std::string body_line(const Body& b) {
    std::string s =
        std::string("body ") + (b.is_static ? "static" : "dynamic") + " " + exact(b.mass);
    for (const Vec3* v : {&b.half_extents, &b.position, &b.velocity})
      s += " " + exact(v->x()) + " " + exact(v->y()) + " " + exact(v->z());
    return s;
  }

  // Records the failure, stops the engine and throws: "at step 12: the engine crashed: SIGSEGV".
  [[noreturn]] void fail(const std::string& what) {
    failure_ = where_ + ": " + what;
    if (child_) child_->stop();
    throw EngineError(failure_);
  }

  // How the engine went away: "crashed: SIGSEGV" or "exited early (exited with status 0)".
  std::string gone() {
    const std::string status = child_->exit_description(1.0);
    if (status.rfind("crashed", 0) == 0) return "the engine " + status;
    return "the engine exited early (" + status + ")";
  }

  void send(const std::string& line) {
    switch (child_->write_line(line, spec_.timeout_s)) {
      case IoStatus::ok:
        return;
      case IoStatus::timeout:
        fail("the engine did not read its input within " + format_seconds(spec_.timeout_s) +
             " (timeout; engine killed)");
      default:
        fail(gone());
    }
  }

  // The next line from the engine; an "error TEXT" line fails with TEXT.
  std::string receive() {
    std::string line;
    switch (child_->read_line(line, spec_.timeout_s)) {
      case IoStatus::ok:
        break;
      case IoStatus::timeout:
        fail("no answer within " + format_seconds(spec_.timeout_s) + " (timeout; engine killed)");
      case IoStatus::too_long:
        fail("garbage from the engine: a line longer than 1 MiB");
      case IoStatus::closed:
        fail(gone());
    }
    if (line.rfind("error", 0) == 0 && (line.size() == 5 || line[5] == ' ' || line[5] == '\t'))
      fail("the engine reported an error: " + rest_of(line));
    return line;
  }

  void garbage(const std::string& expected, const std::string& line) {
    fail("garbage from the engine: expected " + expected + ", got " + quote(line));
  }

  // "state N" and 6 numbers (x y z vx vy vz) per body.
  void read_state(std::int64_t n) {
    const std::string line = receive();
    const std::vector<std::string> t = split(line);
    const std::string head = "'state " + std::to_string(n) + "'";
    const std::size_t want = 6 * states_.size();
    if (t.size() < 2 || t[0] != "state" || t[1] != std::to_string(n))
      garbage(head + " and " + std::to_string(want) + " numbers", line);
    const std::size_t got = t.size() - 2;
    if (got != want) {
      const std::string per_body = got % 6 == 0 ? " (" + std::to_string(got / 6) + " bodies)" : "";
      fail("the engine answered " + std::to_string(got) + " numbers" + per_body +
           ", the scene has " + std::to_string(states_.size()) + " bodies (" +
           std::to_string(want) + " numbers)");
    }
    for (std::size_t i = 0; i < got; ++i) {
      double v = 0.0;
      if (!parse_number(t[2 + i], v)) garbage("a number", t[2 + i]);
      BodyState& s = states_[i / 6];
      (i % 6 < 3 ? s.position : s.velocity)[static_cast<Eigen::Index>(i % 3)] = v;
    }
  }

  void handshake() {
    where_ = "at start";
    const std::string first = receive();
    const std::vector<std::string> t = split(first);
    if (t.size() != 2 || t[0] != "dropcheck-engine") garbage("'dropcheck-engine 1'", first);
    if (t[1] != std::to_string(kProtocolVersion))
      fail("the engine speaks protocol " + quote(t[1]) + "; dropcheck speaks " +
           std::to_string(kProtocolVersion));
    bool name = false, version = false, scalar = false, law = false;
    for (;;) {
      const std::string line = receive();
      const std::vector<std::string> k = split(line);
      if (k.size() == 1 && k[0] == "ready") break;
      if (k.empty()) garbage("a handshake line", line);
      const std::string value = rest_of(line);
      if (k[0] == "name" && k.size() == 2) {
        if (spec_.name.empty()) {
          if (std::string p = name_problem(k[1]); !p.empty()) fail(p);
          info_.name = k[1];
        }
        name = true;
      } else if (k[0] == "version" && k.size() >= 2) {
        info_.version = value;
        version = true;
      } else if (k[0] == "scalar" && k.size() == 2 && (k[1] == "f32" || k[1] == "f64")) {
        info_.scalar = k[1] == "f32" ? Scalar::f32 : Scalar::f64;
        scalar = true;
      } else if (k[0] == "law" && k.size() == 2 && parse_law_key(k[1])) {
        info_.law = *parse_law_key(k[1]);
        law = true;
      } else if (k[0] == "capabilities") {
        for (std::size_t i = 1; i < k.size(); ++i) {
          if (k[i] == "contacts")
            info_.capabilities.contacts = true;
          else if (k[i] == "planar-only")
            info_.capabilities.planar_only = true;
          else if (k[i] == "continuous-collision")
            info_.continuous_collision = true;
          else
            garbage("capabilities 'contacts', 'planar-only' or 'continuous-collision'", line);
        }
      } else if (k[0] == "damping-mapping" && k.size() >= 2) {
        info_.damping_mapping = value;
      } else {
        garbage(
            "name, version, scalar f32|f64, law KEY, capabilities, damping-mapping or ready "
            "(law keys: after-forces, before-forces, after-position, after-forces/explicit, "
            "before-forces/explicit)",
            line);
      }
    }
    if (!name || !version || !scalar || !law)
      fail("the handshake lacks " + std::string(!name      ? "name"
                                                : !version ? "version"
                                                : !scalar  ? "scalar"
                                                           : "law"));
  }

  ExecSpec spec_;
  std::unique_ptr<ChildProcess> child_;
  EngineInfo info_;
  std::string failure_;  // not empty once the engine failed: every later call rethrows it
  std::string where_;    // "at start", "at load", "at step N": prefix of failure messages
  std::vector<BodyState> states_;
  std::vector<Vec3> forces_;
  std::int64_t step_ = 0;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool executable_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

int line_of(const toml::node& n) {
  return static_cast<int>(n.source().begin.line);
}

ExecSpec parse_engine_file(const std::string& file) {
  toml::table table;
  try {
    table = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    const std::string what(e.description());
    if (!std::filesystem::exists(file)) throw InputError(file, 0, "", "no such engine file");
    throw InputError(file, static_cast<int>(e.source().begin.line), "", what);
  }
  ExecSpec spec;
  spec.cwd = std::filesystem::absolute(file).parent_path().string();
  for (const auto& [key, node] : table) {
    const std::string k(key.str());
    if (k == "name") {
      const auto* s = node.as_string();
      if (!s) throw InputError(file, line_of(node), k, "must be a string");
      spec.name = s->get();
      if (std::string p = name_problem(spec.name); !p.empty())
        throw InputError(file, line_of(node), k, p);
    } else if (k == "command") {
      const auto* a = node.as_array();
      if (!a || a->empty())
        throw InputError(file, line_of(node), k, "must be a non-empty array of strings");
      for (const toml::node& arg : *a) {
        const auto* s = arg.as_string();
        if (!s || (spec.command.empty() && s->get().empty()))
          throw InputError(file, line_of(node), k, "must be a non-empty array of strings");
        spec.command.push_back(s->get());
      }
    } else if (k == "timeout") {
      const std::optional<double> v = node.value<double>();
      if (!v || !(*v > 0.0 && *v <= 3600.0))
        throw InputError(file, line_of(node), k, "must be a number of seconds in (0, 3600]");
      spec.timeout_s = *v;
    } else {
      throw InputError(file, line_of(node), k, "unknown key (known: name, command, timeout)");
    }
  }
  if (spec.command.empty())
    throw InputError(file, 0, "command", "missing (the program and its arguments)");
  return spec;
}

}  // namespace

bool is_exec_spec(const std::string& name) {
  return name.rfind("exec:", 0) == 0 || ends_with(name, ".toml");
}

ExecSpec parse_exec_spec(const std::string& name) {
  if (name.rfind("exec:", 0) != 0) return parse_engine_file(name);
  const std::string path = name.substr(5);
  if (!executable_file(path))
    throw InputError("", 0, "--engine " + name, "'" + path + "' is not an executable file");
  ExecSpec spec;
  spec.command = {path.find('/') == std::string::npos ? "./" + path : path};
  return spec;
}

std::unique_ptr<Engine> make_exec_engine(const ExecSpec& spec) {
  return std::make_unique<ExecEngine>(spec);
}

}  // namespace dropcheck
