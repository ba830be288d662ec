// Adapter for external engines: a child process speaking docs/protocol.md over stdin/stdout.
//
// Mapping (scene -> protocol): the scene is sent once per load() ("scene" ... "end": h, gravity,
// damping rate k with phi = exp(-k*h), contacts flag, one "body" line per body); each step sends
// the harness's forces and reads back every body's position and velocity. A rotating scene (only
// for an engine that announced rotation) adds the angular damping, each body's orientation,
// angular velocity and moments, each step's torques, and the rotation in every state. Numbers go
// out with %.17g and come back through std::from_chars, so nothing is lost at the boundary. Every
// failure of the engine (cannot start, crash, hang, garbage, wrong body count, early exit, "error
// TEXT") is an EngineError naming the step; the child is then killed and reaped.
#include "exec.hpp"

#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "exec_protocol.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/process/child_process.hpp"
#include "harness/scene/toml_ascii.hpp"

namespace dropcheck {
namespace {

// Largest engine file read (a few lines of TOML in practice).
constexpr std::int64_t kMaxEngineFileBytes = 64 * 1024;

std::string format_seconds(double s) {
  return sig(s, 6) + " s";
}

// Appends " c0 c1 ..." to a protocol line, each coefficient of `v` exactly (appended piece by
// piece: GCC 12 warns falsely on " " + std::string at -O3).
template <class Vector>
void append_words(std::string& line, const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    line += ' ';
    line += exact(v[i]);
  }
}

class ExecEngine final : public Engine {
 public:
  explicit ExecEngine(ExecSpec spec) : spec_(std::move(spec)) {
    // Until the handshake names it (or when it never does): the engine file's stem, else the
    // program's, so that two engine files that both fail to start keep apart.
    const std::string& named_by = spec_.file.empty() ? spec_.command[0] : spec_.file;
    info_.name = spec_.name.empty()
                     ? escape_controls(std::filesystem::path(named_by).stem().string())
                     : spec_.name;
    info_.version.assign(1, '?');  // (= "?" draws GCC 12's false -Wrestrict at -O3)
    info_.own_process = true;
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
    if (!failure_.empty()) rethrow();
    const std::size_t n = scene.bodies.size();
    states_.assign(n, {});
    forces_.assign(n, Vec3::Zero());
    // A rotating scene reaches only an engine that announced rotation (Engine::cannot_run): its
    // bodies, steps and states then carry the rotation (docs/protocol.md 3.6).
    rotating_ = needs_rotation(scene);
    turns_.assign(rotating_ ? n : 0, {});
    torques_.assign(rotating_ ? n : 0, Vec3::Zero());
    step_ = 0;
    where_ = "at load";
    send("scene " + std::to_string(n));
    send("h " + exact(h));
    const Vec3& g = scene.world.gravity;
    send("gravity " + exact(g.x()) + " " + exact(g.y()) + " " + exact(g.z()));
    send("damping " + exact(scene.world.damping_rate) + " " + exact(decay_per_step(scene, h)));
    send(std::string("contacts ") + (scene.world.contacts ? "1" : "0"));
    if (rotating_)
      send("angular-damping " + exact(scene.world.angular_damping_rate) + " " +
           exact(angular_decay_per_step(scene, h)));
    // Only a scene that sets them sends materials and shapes (an engine that announced friction,
    // restitution or spheres; the others never get such a scene: Engine::cannot_run).
    const Material m = scene_material(scene);
    if (m.friction || m.restitution)
      send("material " + (m.friction ? exact(*m.friction) : "-") + " " +
           (m.restitution ? exact(*m.restitution) : "-"));
    const bool shapes = has_spheres(scene);
    for (const Body& b : scene.bodies)
      send(body_line(b, rotating_) +
           (shapes ? (b.shape == Shape::sphere ? " sphere" : " box") : ""));
    send("end");
    read_state(0);
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < forces_.size() && i < forces.size(); ++i) forces_[i] = forces[i];
  }

  void step() override {
    if (!failure_.empty()) rethrow();
    ++step_;
    where_ = "at step " + std::to_string(step_);
    std::string line = "step " + std::to_string(step_);
    for (const Vec3& f : forces_) append_words(line, f);
    for (Vec3& t : torques_) {
      append_words(line, t);
      t.setZero();  // this step only (Engine::set_torques)
    }
    send(line);
    read_state(step_);
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < torques_.size() && i < torques.size(); ++i)
      torques_[i] = torques[i];
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < turns_.size() && i < out.size(); ++i) out[i] = turns_[i];
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < states_.size() && i < out.size(); ++i) out[i] = states_[i];
  }

 private:
  // "body dynamic M HX HY HZ X Y Z VX VY VZ", and in a rotating scene "QW QX QY QZ WX WY WZ IXX
  // IYY IZZ" after them.
  static std::string body_line(const Body& b, bool rotating) {
    std::string s =
        std::string("body ") + (b.is_static ? "static" : "dynamic") + " " + exact(b.mass);
    const Vec3 inertia = inertia_of(b);
    for (const Vec3* v : {&b.half_extents, &b.position, &b.velocity}) append_words(s, *v);
    if (!rotating) return s;
    const Quat& q = b.orientation;
    append_words(s, Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
    for (const Vec3* v : {&b.angular_velocity, &inertia}) append_words(s, *v);
    return s;
  }

  // Records the failure, stops the engine and throws: "at step 12: garbage from the engine ...".
  [[noreturn]] void fail(const std::string& what) {
    failure_ = where_ + ": " + what;
    if (child_) child_->stop();
    rethrow();
  }

  // The recorded failure again: EngineDied when the engine's process went away (the run's status
  // is then crashed, as for a built-in engine whose process died), else EngineError.
  [[noreturn]] void rethrow() const {
    if (died_) throw EngineDied(failure_);
    throw EngineError(failure_);
  }

  // The engine's process went away: "the engine crashed: SIGSEGV", "the engine exited early
  // (exited with status 1)"; one that closed its output but still runs is killed.
  [[noreturn]] void gone() {
    const std::string status = child_->exit_description(1.0);
    died_ = true;
    if (status.rfind("crashed", 0) == 0) fail("the engine " + status);
    if (status == "still running")
      fail("the engine closed its output but kept running (engine killed)");
    fail("the engine exited early (" + status + ")");
  }

  void send(const std::string& line) {
    switch (child_->write_line(line, spec_.timeout_s)) {
      case IoStatus::ok:
        return;
      case IoStatus::timeout:
        fail("the engine did not read its input within " + format_seconds(spec_.timeout_s) +
             " (timeout; engine killed)");
      default:
        gone();
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
        gone();
    }
    if (is_error_line(line)) fail("the engine reported an error: " + error_text(line));
    return line;
  }

  void read_state(std::int64_t n) {
    const std::string line = receive();
    try {
      if (rotating_)
        parse_state_line(line, n, states_, turns_);
      else
        parse_state_line(line, n, states_);
    } catch (const ProtocolError& e) {
      fail(e.what());
    }
  }

  void handshake() {
    where_ = "at start";
    HandshakeReader reader(info_, !spec_.name.empty(), known_engine_names());
    try {
      while (!reader.take(receive())) {
      }
    } catch (const ProtocolError& e) {
      fail(e.what());
    }
  }

  ExecSpec spec_;
  std::unique_ptr<ChildProcess> child_;
  EngineInfo info_;
  std::string failure_;  // not empty once the engine failed: every later call rethrows it
  bool died_ = false;    // the failure is the engine's process going away
  std::string where_;    // "at start", "at load", "at step N": prefix of failure messages
  std::vector<BodyState> states_;
  std::vector<Vec3> forces_;
  bool rotating_ = false;             // the scene loaded needs rotation
  std::vector<RotationState> turns_;  // its bodies' rotation after the last answer
  std::vector<Vec3> torques_;         // this step's torques (rotating scenes)
  std::int64_t step_ = 0;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

int line_of(const toml::node& n) {
  return static_cast<int>(n.source().begin.line);
}

// Why the command's program cannot be started, when that can be told before starting it: a path
// (with '/') is resolved against the engine file's folder and must be an executable regular file.
// A bare name is searched in PATH when the engine starts.
std::string program_problem(const std::string& program, const std::string& cwd) {
  if (program.find('/') == std::string::npos) return {};
  const std::filesystem::path p = program[0] == '/' || cwd.empty()
                                      ? std::filesystem::path(program)
                                      : std::filesystem::path(cwd) / program;
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return excerpt(program) + ": " + std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return excerpt(program) + " is a folder, not a program";
  if (!S_ISREG(st.st_mode) || ::access(p.c_str(), X_OK) != 0)
    return excerpt(program) + " is not an executable file";
  return {};
}

ExecSpec parse_engine_file(const std::string& file) {
  // Read as a scene file is: a regular file of bounded size (a device or FIFO is refused at once),
  // UTF-8 without control characters, non-ASCII only in strings and comments.
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file, 0, "", "no such engine file");
  const std::string text =
      read_regular_file(file, kMaxEngineFileBytes, "64 KiB, for an engine file");
  toml::table table;
  try {
    table = toml::parse(toml_as_ascii(text, file), file);
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<int>(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  ExecSpec spec;
  spec.file = file;
  spec.cwd = std::filesystem::absolute(file).parent_path().string();
  for (const auto& [key, node] : table) {
    const std::string k(key.str());
    if (k == "name") {
      const auto* s = node.as_string();
      if (!s) throw InputError(file, line_of(node), k, "must be a string");
      spec.name = s->get();
      if (std::string p = engine_name_problem(spec.name, known_engine_names()); !p.empty())
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
  if (std::string p = program_problem(spec.command[0], spec.cwd); !p.empty())
    throw InputError(file, line_of(*table.get("command")), "command", p);
  return spec;
}

}  // namespace

bool is_exec_spec(const std::string& name) {
  return name.rfind("exec:", 0) == 0 || ends_with(name, ".toml");
}

ExecSpec parse_exec_spec(const std::string& name) {
  if (name.rfind("exec:", 0) != 0) return parse_engine_file(name);
  const std::string path = name.substr(5);
  ExecSpec spec;
  spec.command = {path.find('/') == std::string::npos ? "./" + path : path};
  if (std::string p = program_problem(spec.command[0], ""); !p.empty())
    throw InputError("", 0, "--engine " + excerpt(name), p);
  return spec;
}

// The largest file an external engine's fingerprint reads (a script, a compiled engine), and the
// most files one command may name.
constexpr std::int64_t kMaxFingerprintBytes = 64LL << 20;
constexpr std::size_t kMaxFingerprintFiles = 32;

std::optional<ExternalEngineId> external_engine_id(const std::string& name) {
  if (!is_exec_spec(name)) return std::nullopt;
  const ExecSpec spec = parse_exec_spec(name);
  const std::string where = spec.file.empty() ? name : spec.file;
  // Each part by its tag, its file name and the FNV-1a of its bytes: one file in memory at a time.
  std::string parts;
  const auto add = [&](const char* tag, const std::filesystem::path& file, std::int64_t limit,
                       const char* limit_text) {
    parts += std::string(tag) + '\0' + file.filename().string() + '\0' +
             fnv1a_hex(read_regular_file(file.string(), limit, limit_text)) + '\n';
  };
  if (!spec.file.empty())
    add("engine-file", spec.file, kMaxEngineFileBytes, "64 KiB, for an engine file");
  std::set<std::filesystem::path> files;
  for (const std::string& word : spec.command) {
    std::filesystem::path p(word);
    if (p.is_relative() && !spec.cwd.empty()) p = std::filesystem::path(spec.cwd) / p;
    std::error_code ec;
    if (word.empty() || !std::filesystem::is_regular_file(p, ec)) continue;
    if (!files.insert(p.lexically_normal()).second) continue;
    if (files.size() > kMaxFingerprintFiles)
      throw InputError(where, 0, "command",
                       "names more than " + std::to_string(kMaxFingerprintFiles) +
                           " files, the most a fingerprint reads");
    add("runs", p, kMaxFingerprintBytes, "64 MiB, for a file an external engine runs");
  }
  ExternalEngineId id;
  id.name = !spec.name.empty()  ? spec.name
            : spec.file.empty() ? std::filesystem::path(spec.command[0]).filename().string()
                                : std::filesystem::path(spec.file).stem().string();
  if (std::string p = engine_name_problem(id.name, known_engine_names()); !p.empty())
    throw InputError(where, 0, spec.file.empty() ? "exec:" : "name",
                     p + " (an engine file's `name` key names it)");
  id.fingerprint = fnv1a_hex(parts);
  return id;
}

bool is_external_engine_name(const std::string& name) {
  return is_exec_spec(name);
}

bool is_external_engine_id(const std::string& id) {
  const std::size_t at = id.rfind('@');
  return at != std::string::npos && engine_name_problem(id.substr(0, at), {}).empty() &&
         id.size() == at + 17 &&
         id.find_first_not_of("0123456789abcdef", at + 1) == std::string::npos;
}

std::unique_ptr<Engine> make_exec_engine(const ExecSpec& spec) {
  return std::make_unique<ExecEngine>(spec);
}

}  // namespace dropcheck
