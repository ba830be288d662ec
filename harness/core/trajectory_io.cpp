#include "harness/core/trajectory_io.hpp"

#include <cmath>
#include <cstdio>

namespace dropcheck {
namespace {

// ",x,y,z" for each vector.
void append_csv(std::string& out, const Vec3& v) {
  for (int i = 0; i < 3; ++i) out += "," + exact(v[i]);
}

// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// JSON has no NaN or Inf: write null for them.
std::string json_number(double v) { return std::isfinite(v) ? exact(v) : "null"; }

std::string json_vec(const Vec3& v) {
  return "[" + json_number(v[0]) + "," + json_number(v[1]) + "," + json_number(v[2]) + "]";
}

}  // namespace

std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string trajectories_to_csv(std::span<const Trajectory> runs) {
  std::string out = "engine,dt,step,t,body,x,y,z,vx,vy,vz\n";
  for (const Trajectory& t : runs) {
    for (std::size_t s = 0; s < t.samples(); ++s) {
      for (std::size_t b = 0; b < t.bodies(); ++b) {
        const BodyState& st = t.at(s, b);
        out += csv_field(t.engine) + "," + exact(t.h) + "," + std::to_string(t.recorded[s]) + "," +
               exact(t.time(s)) + "," + csv_field(t.body_names[b]);
        append_csv(out, st.position);
        append_csv(out, st.velocity);
        out += '\n';
      }
    }
  }
  return out;
}

std::string trajectories_to_json(std::span<const Trajectory> runs) {
  std::string out = "{\"runs\":[";
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Trajectory& t = runs[r];
    out += r ? ",\n" : "\n";
    out += "{\"engine\":" + json_string(t.engine) + ",\"scene\":" + json_string(t.scene) +
           ",\"dt\":" + exact(t.h) + ",\"steps\":" + std::to_string(t.steps) +
           ",\"status\":" + json_string(to_string(t.status)) + ",\"failure\":" + json_string(t.failure) +
           ",\"failed_step\":" + std::to_string(t.failed_step) +
           ",\"clamped_steps\":" + std::to_string(t.clamped_steps) + ",\"bodies\":[";
    for (std::size_t b = 0; b < t.bodies(); ++b) {
      out += (b ? ",{" : "{") + std::string("\"name\":") + json_string(t.body_names[b]) + ",\"samples\":[";
      for (std::size_t s = 0; s < t.samples(); ++s) {
        const BodyState& st = t.at(s, b);
        out += (s ? ",[" : "[") + std::to_string(t.recorded[s]) + "," + json_vec(st.position) + "," +
               json_vec(st.velocity) + "]";
      }
      out += "]}";
    }
    out += "]}";
  }
  return out + "\n]}\n";
}

}  // namespace dropcheck
