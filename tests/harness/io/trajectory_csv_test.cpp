// Tests harness/io/trajectory_csv.cpp, the reader of `identify --trajectory`: numbers that are not
// numbers (NaN, infinities) are refused with line and column before any fit, a UTF-8 byte-order
// mark is accepted, and a refusal quotes only a short, escaped excerpt of the file.
#include "harness/io/trajectory_csv.hpp"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>

#include "harness/core/input_error.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;

namespace {

const std::string kHeader = "engine,dt,step,t,body,x,y,z,vx,vy,vz\n";
const std::string kRow0 = "e,0.5,0,0,c,0,10,0,0,0,0\n";

std::vector<Trajectory> parse_csv(const std::string& text) {
  std::istringstream in(text);
  return parse_trajectories_csv(in, "run.csv");
}

std::string csv_error_of(const std::string& text) {
  try {
    parse_csv(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST_CASE("a NaN or infinite number in any numeric column is refused with line and column",
          "[csv]") {
  CHECK(csv_error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,nan,10,0,0,0,0\n") ==
        "run.csv:3: x (column 6): 'nan' is not a finite number (no verdict can be fitted to it)");
  CHECK_THAT(csv_error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,0,10,0,0,-inf,0\n"),
             Contains("run.csv:3: vy (column 10): '-inf' is not a finite number"));
  CHECK_THAT(csv_error_of(kHeader + "e,0.5,0,inf,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: t (column 4): 'inf' is not a finite number"));
  CHECK_THAT(csv_error_of(kHeader + "e,NaN,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: dt (column 2): 'NaN' is not a finite number"));
  CHECK_THAT(csv_error_of(kHeader + "e,1e999,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: dt (column 2): '1e999' is not a number"));
  CHECK(csv_error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,0,9,0,0,-1,0\n") == "(read)");
  // Each number finite, but step x dt, the time dropcheck uses, is not.
  CHECK_THAT(
      csv_error_of(kHeader + "e,1e308,0,0,c,0,10,0,0,0,0\ne,1e308,2,0,c,0,10,0,0,0,0\n"),
      Contains("run.csv:3: step (column 3): step x dt is not a finite time ('2' x '1e308')"));
  // CRLF line ends, the last line without one.
  CHECK(parse_csv(kHeader + "e,0.5,0,0,c,0,10,0,0,0,0\r\ne,0.5,1,0.5,c,0,9,0,0,-1,0\r").size() ==
        1);
}

TEST_CASE("a UTF-8 byte-order mark before the header is accepted, as in scenes", "[csv]") {
  const std::vector<Trajectory> runs = parse_csv("\xef\xbb\xbf" + kHeader + kRow0);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].engine == "e");
  CHECK(runs[0].at(0, 0).position.y() == 10.0);
  // Anywhere else it is not the header.
  CHECK_THAT(csv_error_of("x\xef\xbb\xbf" + kHeader + kRow0), Contains("the header must be"));
}

TEST_CASE("a refusal quotes a short, escaped excerpt, never the field or line whole", "[csv]") {
  const std::string field(50'000, '7');
  const std::string huge = csv_error_of(kHeader + "e,0.5,0,0,c," + field + "x,10,0,0,0,0\n");
  CHECK_THAT(huge, Contains("x (column 6): '777"));
  CHECK_THAT(huge, Contains("... (50001 bytes) is not a number"));
  CHECK(huge.size() < 200);
  const std::string line(70'000, 'a');
  CHECK(csv_error_of(kHeader + line + "\n") ==
        "run.csv:2: a line longer than 64 KiB: not a trajectory CSV");
  CHECK(csv_error_of(kHeader + "e,0.5,0,0,c,\x1b[2J,10,0,0,0,0\n") ==
        "run.csv:2: x (column 6): '\\x1b[2J' is not a number");
}

TEST_CASE("an engine or body name with a control character is refused", "[csv]") {
  CHECK_THAT(csv_error_of(kHeader + "\"e\x1b]0;owned\x07\",0.5,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: engine (column 1): 'e\\x1b]0;owned\\x07' is not a name"));
  CHECK_THAT(csv_error_of(kHeader + "e,0.5,0,0,\"a\tb\",0,10,0,0,0,0\n"),
             Contains("run.csv:2: body (column 5): 'a\\x09b' is not a name"));
}

namespace {

// A run written as Gazebo's benchmark tools write it (tools/mcap_to_csv.py): the state turned back
// into Gazebo's z-up frame by the inverse of (x, y, z) -> (x, z, -y).
std::string as_gazebo_log(const Trajectory& t) {
  const auto back = [](const Vec3& v) { return Vec3(v.x(), -v.z(), v.y()); };
  const Quat m(std::sqrt(0.5), -std::sqrt(0.5), 0.0, 0.0);
  std::ostringstream out;
  out.precision(17);
  out << "physics_engine,time_step,complex,collisiion,model_count,wall_time,log_multiple,"
         "classname\n"
      << t.engine << "," << t.h << ",1,0,1,0.5,1,Boxes\n"
      << "sim_time,model_no,linear_velocity_x,linear_velocity_y,linear_velocity_z,"
         "angular_velocity_x,angular_velocity_y,angular_velocity_z,position_x,position_y,"
         "position_z,quaternion_w,quaternion_x,quaternion_y,quaternion_z\n";
  for (std::size_t s = 0; s < t.samples(); ++s) {
    const Vec3 v = back(t.at(s, 0).velocity), x = back(t.at(s, 0).position);
    const Vec3 w = back(t.rotation_at(s, 0).angular_velocity);
    const Quat q = m.conjugate() * t.rotation_at(s, 0).orientation * m;
    out << t.time(s) + t.h << ",0," << v.x() << "," << v.y() << "," << v.z() << "," << w.x() << ","
        << w.y() << "," << w.z() << "," << x.x() << "," << x.y() << "," << x.z() << "," << q.w()
        << "," << q.x() << "," << q.y() << "," << q.z() << "\n";
  }
  return out.str();
}

}  // namespace

TEST_CASE("a Gazebo benchmark log is read in dropcheck's frame, its steps from its first row",
          "[csv][rotation]") {
  Trajectory t;
  t.engine = "bullet";
  t.h = 0.001;
  t.body_names = {"box"};
  t.rotates = true;
  for (std::int64_t n = 0; n < 3; ++n) {
    const double a = 0.1 * static_cast<double>(n);
    t.recorded.push_back(n);
    t.states.push_back({Vec3(1.0 + a, 2.0, -3.0), Vec3(-2.0, 8.0 - a, -2.0)});
    t.rotations.push_back({Quat(Eigen::AngleAxisd(a, Vec3(0.6, 0.0, 0.8))), Vec3(0.1, 0.1, -5.0)});
  }
  std::istringstream in(as_gazebo_log(t));
  const std::vector<Trajectory> runs = parse_trajectories_csv(in, "boxes.csv");
  REQUIRE(runs.size() == 1);
  const Trajectory& r = runs[0];
  CHECK(r.engine == "bullet");
  CHECK(r.h == 0.001);
  CHECK(r.recorded == std::vector<std::int64_t>{0, 1, 2});  // sim_time 0.001.. counted from row 1
  CHECK(r.body_names == std::vector<std::string>{"model_0"});
  REQUIRE(r.rotates);
  for (std::size_t s = 0; s < 3; ++s) {
    CHECK((r.at(s, 0).position - t.at(s, 0).position).norm() < 1e-14);
    CHECK((r.at(s, 0).velocity - t.at(s, 0).velocity).norm() < 1e-14);
    CHECK((r.rotation_at(s, 0).angular_velocity - t.rotation_at(s, 0).angular_velocity).norm() <
          1e-14);
    CHECK(r.rotation_at(s, 0).orientation.angularDistance(t.rotation_at(s, 0).orientation) < 1e-14);
  }
  // Not a unit quaternion: refused with the line and the column.
  std::string bad = as_gazebo_log(t);
  bad.replace(bad.rfind(",0.") + 1, 0, "9");
  std::istringstream in_bad(bad);
  CHECK_THROWS_WITH(
      parse_trajectories_csv(in_bad, "boxes.csv"),
      Contains("boxes.csv:6: quaternion_w (column 12)") || Contains("boxes.csv:6: quaternion"));
}

TEST_CASE("a Gazebo log written model by model is read step by step", "[csv][rotation]") {
  // tools/mcap_to_csv.py writes every step of model 0, then every step of model 1.
  std::istringstream in(
      "physics_engine,time_step,complex,collisiion,model_count,wall_time,log_multiple,classname\n"
      "ode,0.5,1,0,2,0.1,1,Boxes\n"
      "sim_time,model_no,linear_velocity_x,linear_velocity_y,linear_velocity_z,"
      "angular_velocity_x,angular_velocity_y,angular_velocity_z,position_x,position_y,"
      "position_z,quaternion_w,quaternion_x,quaternion_y,quaternion_z\n"
      "0.5,0,0,0,0,0,0,0,1,0,0,1,0,0,0\n"
      "1,0,0,0,0,0,0,0,2,0,0,1,0,0,0\n"
      "0.5,1,0,0,0,0,0,0,10,0,0,1,0,0,0\n"
      "1,1,0,0,0,0,0,0,20,0,0,1,0,0,0\n");
  const std::vector<Trajectory> runs = parse_trajectories_csv(in, "two.csv");
  REQUIRE(runs.size() == 1);
  const Trajectory& t = runs[0];
  CHECK(t.body_names == std::vector<std::string>{"model_0", "model_1"});
  CHECK(t.recorded == std::vector<std::int64_t>{0, 1});
  CHECK(t.at(1, 0).position.x() == 2.0);
  CHECK(t.at(1, 1).position.x() == 20.0);
}

TEST_CASE("a Gazebo log whose time, step x time_step, overflows is refused", "[csv][rotation]") {
  // Found by review of the fuzz target trajectory_csv (fuzz/regressions/trajectory_csv/
  // gazebo_time_overflow.csv): read, the run's last time was inf, which the CSV it prints refuses.
  const std::string columns =
      "sim_time,model_no,linear_velocity_x,linear_velocity_y,linear_velocity_z,"
      "angular_velocity_x,angular_velocity_y,angular_velocity_z,position_x,position_y,"
      "position_z,quaternion_w,quaternion_x,quaternion_y,quaternion_z\n";
  CHECK(csv_error_of("physics_engine,time_step,\node,1e308\n" + columns +
                     "0,0,0,0,0,0,0,0,0,0,0,1,0,0,0\n"
                     "1.79e308,0,0,0,0,0,0,0,0,0,0,1,0,0,0\n") ==
        "run.csv:5: sim_time: step 2 x time_step '1e308' is not a finite time");
}
