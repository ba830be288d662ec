#include "harness/io/trajectory_csv.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"

namespace dropcheck {
namespace {

constexpr const char* kHeader = "engine,dt,step,t,body,x,y,z,vx,vy,vz";
// The header of a run with rotation: the orientation quaternion and world-frame angular velocity.
constexpr const char* kRotationHeader = "engine,dt,step,t,body,x,y,z,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz";
constexpr const char* kByteOrderMark = "\xef\xbb\xbf";  // accepted before the header, as in scenes
constexpr const char* kColumns[] = {"engine", "dt", "step", "t",  "body", "x",  "y",  "z",  "vx",
                                    "vy",     "vz", "qw",   "qx", "qy",   "qz", "wx", "wy", "wz"};
constexpr std::size_t kLinearColumns = 11, kRotationColumns = 18;

// Splits one CSV record (RFC 4180 quoting, as trajectory_io.cpp writes it).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        out.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

// Longest line read (bytes): a row of dropcheck's is under 300; a longer one is not a trajectory,
// and reading it whole would cost its size in memory.
constexpr std::size_t kMaxLine = 64 * 1024;

// The column's name and position for messages: "x (column 6)".
std::string column_key(int column) {
  return std::string(kColumns[column]) + " (column " + std::to_string(column + 1) + ")";
}

// A finite number: NaN and infinities are refused, since every verdict fitted to them is void.
double csv_number(const std::string& s, const std::string& file, int line, int column) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty())
    throw InputError(file, line, column_key(column), excerpt(s) + " is not a number");
  if (!std::isfinite(v))
    throw InputError(file, line, column_key(column),
                     excerpt(s) + " is not a finite number (no verdict can be fitted to it)");
  return v;
}

// The next line of `in` without its line break, at most kMaxLine bytes; false at the end.
bool next_line(std::istream& in, std::string& line, const std::string& file, int n) {
  line.clear();
  std::streambuf* buf = in.rdbuf();
  for (bool any = false;; any = true) {
    const int c = buf->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF without a last newline
      return any;
    }
    if (c == '\n') break;
    if (line.size() == kMaxLine)
      throw InputError(file, n, "", "a line longer than 64 KiB: not a trajectory CSV");
    line.push_back(static_cast<char>(c));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

// The run a row belongs to, created on first sight; `index` finds it by (engine, dt) in log time.
Trajectory& run_for(std::vector<Trajectory>& runs,
                    std::map<std::pair<std::string, double>, std::size_t>& index,
                    const std::string& engine, double dt) {
  const auto [it, added] = index.try_emplace({engine, dt}, runs.size());
  if (added) {
    Trajectory t;
    t.engine = engine;
    t.h = dt;
    runs.push_back(std::move(t));
  }
  return runs[it->second];
}

// Appends one row to its run: a new sample when the step changes.
void add_row(Trajectory& t, std::int64_t step, const std::string& body, const BodyState& s,
             const RotationState* r, const std::string& file, int line) {
  const bool new_sample = t.recorded.empty() || t.recorded.back() != step;
  if (new_sample) {
    if (!t.recorded.empty() && step <= t.recorded.back())
      throw InputError(file, line, "step",
                       "steps of engine " + excerpt(t.engine) + " must increase");
    if (t.recorded.size() >= 1 && t.states.size() != t.recorded.size() * t.body_names.size())
      throw InputError(file, line, "body",
                       "step " + std::to_string(t.recorded.back()) + " lacks bodies of step " +
                           std::to_string(t.recorded[0]));
    t.recorded.push_back(step);
  }
  const std::size_t index = t.states.size() - (t.recorded.size() - 1) * t.body_names.size();
  if (t.recorded.size() == 1) {
    t.body_names.push_back(body);
  } else if (index >= t.body_names.size() || t.body_names[index] != body) {
    throw InputError(
        file, line, "body",
        excerpt(body) + " where step " + std::to_string(t.recorded[0]) + " has " +
            (index < t.body_names.size() ? excerpt(t.body_names[index]) : "no more bodies"));
  }
  t.states.push_back(s);
  t.rotates = r != nullptr;
  if (r) t.rotations.push_back(*r);
}

// The rotation columns of a row: a unit quaternion (within 1e-6: the file's digits may be short)
// and an angular velocity.
RotationState rotation_columns(const std::vector<std::string>& f, const std::string& file, int n) {
  double q[4];
  for (int i = 0; i < 4; ++i) q[i] = csv_number(f[11 + i], file, n, 11 + i);
  RotationState r;
  r.orientation = Quat(q[0], q[1], q[2], q[3]);
  if (std::abs(r.orientation.norm() - 1.0) > 1e-6)
    throw InputError(file, n, column_key(11),
                     "qw, qx, qy, qz must be a unit quaternion (norm " +
                         printf_string("%.9g", r.orientation.norm()) + ")");
  for (int i = 0; i < 3; ++i) r.angular_velocity[i] = csv_number(f[15 + i], file, n, 15 + i);
  return r;
}

// --- Gazebo's physics benchmark logs ----------------------------------------------------------
// scpeters/benchmark's tools/mcap_to_csv.py writes one run per file: a line of run fields, their
// values, then one row per model per step in Gazebo's z-up world frame.
constexpr const char* kGazeboRunHeader = "physics_engine,time_step,";
constexpr const char* kGazeboColumns[] = {
    "sim_time",          "model_no",           "linear_velocity_x",  "linear_velocity_y",
    "linear_velocity_z", "angular_velocity_x", "angular_velocity_y", "angular_velocity_z",
    "position_x",        "position_y",         "position_z",         "quaternion_w",
    "quaternion_x",      "quaternion_y",       "quaternion_z"};

std::string gazebo_header() {
  std::string h;
  for (const char* c : kGazeboColumns) {
    if (!h.empty()) h += ',';
    h += c;
  }
  return h;
}

double gazebo_number(const std::vector<std::string>& f, int i, const std::string& file, int line) {
  double v = 0.0;
  const std::string& s = f[static_cast<std::size_t>(i)];
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  const std::string key =
      std::string(kGazeboColumns[i]) + " (column " + std::to_string(i + 1) + ")";
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty())
    throw InputError(file, line, key, excerpt(s) + " is not a number");
  if (!std::isfinite(v)) throw InputError(file, line, key, excerpt(s) + " is not a finite number");
  return v;
}

// Gazebo's z-up world in dropcheck's y-up one: the proper rotation M: (x, y, z) -> (x, z, -y), a
// turn of -90 degrees about x (never a reflection: it would turn the angular velocity, a
// pseudovector, the wrong way). Orientations: R' = M*R*M^T, the body frame turned with the world
// (a box of sides a x b x c along Gazebo's body axes has sides a x c x b along dropcheck's).
Vec3 from_gazebo(const Vec3& v) {
  return {v.x(), v.z(), -v.y()};
}
Quat from_gazebo(const Quat& q) {
  const Quat m(std::sqrt(0.5), -std::sqrt(0.5), 0.0, 0.0);
  return m * q * m.conjugate();
}

// One Gazebo log as one run, steps counted from its first row.
std::vector<Trajectory> parse_gazebo_log(std::istream& in, const std::string& file) {
  std::string line;
  if (!next_line(in, line, file, 2))
    throw InputError(file, 2, "", "a Gazebo benchmark log needs its run values on line 2");
  const std::vector<std::string> run = csv_fields(line);
  if (run.size() < 2) throw InputError(file, 2, "", "expected physics_engine,time_step,...");
  Trajectory t;
  t.engine = run[0];
  if (t.engine.empty() || find_unsafe_in_line(t.engine) != std::string::npos)
    throw InputError(file, 2, "physics_engine", excerpt(t.engine) + " is not a name");
  const auto [ptr, ec] = std::from_chars(run[1].data(), run[1].data() + run[1].size(), t.h);
  if (ec != std::errc() || ptr != run[1].data() + run[1].size() || !(t.h > 0.0) ||
      !std::isfinite(t.h))
    throw InputError(file, 2, "time_step", excerpt(run[1]) + " is not a step > 0 (s)");
  if (!next_line(in, line, file, 3) || line != gazebo_header())
    throw InputError(file, 3, "", "the columns must be " + gazebo_header());
  t.rotates = true;
  // Rows may come model by model (tools/mcap_to_csv.py writes every step of model 0, then model
  // 1, ...): gathered first, then taken step by step, models in order within a step.
  struct Row {
    double step, model;
    BodyState s;
    RotationState r;
    int line;
  };
  std::vector<Row> rows;
  int n = 3;
  double first_time = NAN;
  while (next_line(in, line, file, n + 1)) {
    ++n;
    if (line.empty()) continue;
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != 15)
      throw InputError(file, n, "", "expected 15 columns, got " + std::to_string(f.size()));
    double v[15];
    for (int i = 0; i < 15; ++i) v[i] = gazebo_number(f, i, file, n);
    if (std::isnan(first_time) || v[0] < first_time) first_time = v[0];
    if (v[1] < 0 || v[1] > 1e6 || v[1] != std::floor(v[1]))
      throw InputError(file, n, "model_no", "must be a whole number >= 0");
    Row row{v[0],
            v[1],
            {from_gazebo(Vec3(v[8], v[9], v[10])), from_gazebo(Vec3(v[2], v[3], v[4]))},
            {},
            n};
    row.r.orientation = Quat(v[11], v[12], v[13], v[14]);
    if (std::abs(row.r.orientation.norm() - 1.0) > 1e-6)
      throw InputError(file, n, "quaternion_w (column 12)",
                       "quaternion_w..z must be a unit quaternion (norm " +
                           printf_string("%.9g", row.r.orientation.norm()) + ")");
    row.r.orientation = from_gazebo(row.r.orientation);
    row.r.angular_velocity = from_gazebo(Vec3(v[5], v[6], v[7]));
    rows.push_back(row);
  }
  for (Row& row : rows) {
    row.step = std::round((row.step - first_time) / t.h);
    if (row.step > 9007199254740992.0)
      throw InputError(file, row.line, "sim_time", "beyond 2^53 steps from the first row");
    if (!std::isfinite(row.step * t.h))  // the time dropcheck uses, step x time_step, overflows
      throw InputError(file, row.line, "sim_time",
                       "step " + std::to_string(static_cast<long long>(row.step)) +
                           " x time_step " + excerpt(run[1]) + " is not a finite time");
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return a.step != b.step ? a.step < b.step : a.model < b.model;
  });
  for (const Row& row : rows)
    add_row(t, static_cast<std::int64_t>(row.step),
            "model_" + std::to_string(static_cast<long long>(row.model)), row.s, &row.r, file,
            row.line);
  if (t.recorded.empty()) throw InputError(file, 4, "", "no rows after the columns");
  if (t.states.size() != t.recorded.size() * t.body_names.size())
    throw InputError(file, n, "model_no", "the last step lacks models");
  t.steps = t.recorded.back();
  return {t};
}

}  // namespace

std::vector<Trajectory> read_trajectories_csv(const std::string& file) {
  // The reason, not just the failure: a missing file, no permission, a folder, a device or FIFO
  // (never read: /dev/zero would never end).
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0)
    throw InputError(file, 0, "",
                     std::string("cannot read the trajectory file: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode))
    throw InputError(file, 0, "", "cannot read the trajectory file: it is a directory");
  if (!S_ISREG(st.st_mode))
    throw InputError(
        file, 0, "",
        "cannot read the trajectory file: not a regular file (a device, FIFO or socket)");
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file, 0, "",
                     std::string("cannot read the trajectory file: ") + std::strerror(errno));
  return parse_trajectories_csv(in, file);
}

std::vector<Trajectory> parse_trajectories_csv(std::istream& in, const std::string& file) {
  std::string line;
  const bool got_header = next_line(in, line, file, 1);
  if (line.rfind(kByteOrderMark, 0) == 0) line.erase(0, std::strlen(kByteOrderMark));
  if (got_header && line.rfind(kGazeboRunHeader, 0) == 0) return parse_gazebo_log(in, file);
  if (!got_header || (line != kHeader && line != kRotationHeader))
    throw InputError(
        file, 1, "",
        std::string("the header must be ") + kHeader + " (with rotation: " + kRotationHeader + ")");
  const std::size_t columns = line == kHeader ? kLinearColumns : kRotationColumns;
  std::vector<Trajectory> runs;
  std::map<std::pair<std::string, double>, std::size_t> index;  // runs by (engine, dt)
  int n = 1;
  while (next_line(in, line, file, n + 1)) {
    ++n;
    if (line.empty()) continue;
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != columns)
      throw InputError(file, n, "",
                       "expected " + std::to_string(columns) + " columns (" +
                           (columns == kLinearColumns ? kHeader : kRotationHeader) + "), got " +
                           std::to_string(f.size()));
    const double dt = csv_number(f[1], file, n, 1);
    const double step = csv_number(f[2], file, n, 2);
    csv_number(f[3], file, n, 3);  // t: checked, not used (the step and dt give the time exactly)
    if (!(dt > 0.0)) throw InputError(file, n, column_key(1), "must be > 0");
    if (step < 0 || step > 9007199254740992.0 ||
        step != static_cast<double>(static_cast<std::int64_t>(step)))
      throw InputError(file, n, column_key(2), "must be a whole number >= 0");
    if (!std::isfinite(step * dt))  // the time dropcheck uses, step x dt, overflows
      throw InputError(
          file, n, column_key(2),
          "step x dt is not a finite time (" + excerpt(f[2]) + " x " + excerpt(f[1]) + ")");
    BodyState s;
    for (int i = 0; i < 3; ++i) {
      s.position[i] = csv_number(f[5 + i], file, n, 5 + i);
      s.velocity[i] = csv_number(f[8 + i], file, n, 8 + i);
    }
    for (int column : {0, 4})  // names reach terminals and reports: no control characters
      if (f[column].empty() || find_unsafe_in_line(f[column]) != std::string::npos)
        throw InputError(file, n, column_key(column),
                         excerpt(f[column]) + " is not a name (empty, or control characters)");
    const RotationState r =
        columns == kRotationColumns ? rotation_columns(f, file, n) : RotationState{};
    add_row(run_for(runs, index, f[0], dt), static_cast<std::int64_t>(step), f[4], s,
            columns == kRotationColumns ? &r : nullptr, file, n);
  }
  for (Trajectory& t : runs) {
    if (t.states.size() != t.recorded.size() * t.body_names.size())
      throw InputError(file, n, "body",
                       "the last step of engine " + excerpt(t.engine) + " lacks bodies");
    t.steps = t.recorded.back();
  }
  if (runs.empty()) throw InputError(file, 2, "", "no rows after the header");
  return runs;
}

}  // namespace dropcheck
