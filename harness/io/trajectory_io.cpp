#include "harness/io/trajectory_io.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "harness/core/number_format.hpp"
#include "harness/io/json_text.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

// ",x,y,z" for each vector.
void append_csv(std::string& out, const Vec3& v) {
  for (int i = 0; i < 3; ++i) {
    out += ',';
    out += exact(v[i]);
  }
}

// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

Json json_vec(const Vec3& v) {
  return Json::array({v[0], v[1], v[2]});
}

// True when some run of `runs` rotates: then every row carries the rotation columns.
bool any_rotates(std::span<const Trajectory> runs) {
  for (const Trajectory& t : runs)
    if (t.rotates) return true;
  return false;
}

// The rotational state of a sample: the run's own, or a body that never turned.
const RotationState& rotation_of(const Trajectory& t, std::size_t sample, std::size_t body) {
  static const RotationState kStill;
  return t.rotates ? t.rotation_at(sample, body) : kStill;
}

// ",qw,qx,qy,qz,wx,wy,wz".
void append_csv(std::string& out, const RotationState& r) {
  const Quat& q = r.orientation;
  for (double d : {q.w(), q.x(), q.y(), q.z()}) {
    out += ',';
    out += exact(d);
  }
  append_csv(out, r.angular_velocity);
}

// The run's fields before its bodies, as nlohmann writes them, without the closing brace.
std::string run_head(const Trajectory& t) {
  const Json run = {{"engine", t.engine},
                    {"scene", t.scene},
                    {"dt", t.h},
                    {"steps", t.steps},
                    {"status", to_string(t.status)},
                    {"failure", t.failure},
                    {"failed_step", t.failed_step},
                    {"clamped_steps", t.clamped_steps}};
  std::string head = json_line(run);
  head.pop_back();
  return head;
}

// One run as {...,"bodies":[{"name":...,"samples":[[t,[x,y,z],[vx,vy,vz]],...]},...]} (a rotating
// run adds [qw,qx,qy,qz],[wx,wy,wz] to each sample), written
// piece by piece in the bytes nlohmann's compact dump of the whole object would give: memory holds
// one sample's text, not the run's document.
void write_run_json(std::ostream& out, const Trajectory& t) {
  out << run_head(t) << ",\"bodies\":[";
  for (std::size_t b = 0; b < t.bodies(); ++b) {
    out << (b ? ",{\"name\":" : "{\"name\":") << json_line(Json(t.body_names[b]))
        << ",\"samples\":[";
    for (std::size_t s = 0; s < t.samples(); ++s) {
      const BodyState& st = t.at(s, b);
      Json sample = Json::array({t.recorded[s], json_vec(st.position), json_vec(st.velocity)});
      if (t.rotates) {
        const RotationState& r = t.rotation_at(s, b);
        const Quat& q = r.orientation;
        sample.push_back(Json::array({q.w(), q.x(), q.y(), q.z()}));
        sample.push_back(json_vec(r.angular_velocity));
      }
      out << (s ? "," : "") << json_line(sample);
    }
    out << "]}";
  }
  out << "]}";
}

}  // namespace

std::string trajectories_to_csv(std::span<const Trajectory> runs) {
  std::ostringstream out;
  write_trajectories_csv(out, runs);
  return out.str();
}

void write_trajectories_csv(std::ostream& out, std::span<const Trajectory> runs) {
  const bool rotation = any_rotates(runs);
  out << (rotation ? "engine,dt,step,t,body,x,y,z,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz\n"
                   : "engine,dt,step,t,body,x,y,z,vx,vy,vz\n");
  std::string row;  // reused: one row's text at a time
  for (const Trajectory& t : runs) {
    const std::string engine = csv_field(t.engine) + "," + exact(t.h) + ",";
    for (std::size_t s = 0; s < t.samples(); ++s) {
      for (std::size_t b = 0; b < t.bodies(); ++b) {
        const BodyState& st = t.at(s, b);
        row = engine;
        row += std::to_string(t.recorded[s]) + "," + exact(t.time(s)) + "," +
               csv_field(t.body_names[b]);
        append_csv(row, st.position);
        append_csv(row, st.velocity);
        if (rotation) append_csv(row, rotation_of(t, s, b));
        row += '\n';
        out.write(row.data(), static_cast<std::streamsize>(row.size()));
      }
    }
  }
}

std::string trajectories_to_json(std::span<const Trajectory> runs) {
  std::ostringstream out;
  write_trajectories_json(out, runs);
  return out.str();
}

void write_trajectories_json(std::ostream& out, std::span<const Trajectory> runs) {
  out << "{\"runs\":[";  // one run per line
  for (std::size_t r = 0; r < runs.size(); ++r) {
    out << (r ? ",\n" : "\n");
    write_run_json(out, runs[r]);
  }
  out << "\n]}\n";
}

}  // namespace dropcheck
