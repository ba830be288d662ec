// Tests the streamed CSV output (write_trajectories_csv through write_file_atomic's buffered
// stream, harness/io/trajectory_io.cpp and atomic_file.cpp): byte for byte the CSV that was
// built whole in memory before, across the 64 KiB buffer's boundaries, and written whole or not at
// all.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "../test_dirs.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/trajectory_io.hpp"

namespace fs = std::filesystem;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

// The CSV exactly as dropcheck built it before streaming: the whole file as one string.
std::string csv_as_before(const dropcheck::Trajectory& t) {
  const auto exact = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  const auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  std::string out = "engine,dt,step,t,body,x,y,z,vx,vy,vz\n";
  for (std::size_t s = 0; s < t.samples(); ++s)
    for (std::size_t b = 0; b < t.bodies(); ++b) {
      out += field(t.engine) + "," + exact(t.h) + "," + std::to_string(t.recorded[s]) + "," +
             exact(t.time(s)) + "," + field(t.body_names[b]);
      for (const dropcheck::Vec3* v : {&t.at(s, b).position, &t.at(s, b).velocity})
        for (int i = 0; i < 3; ++i) out += "," + exact((*v)[i]);
      out += '\n';
    }
  return out;
}

// A run of `samples` samples of two bodies whose names need CSV quoting, with values that print
// at every length %.17g gives.
dropcheck::Trajectory long_run(std::int64_t samples) {
  dropcheck::Trajectory t;
  t.engine = "ours-f64";
  t.h = 1.0 / 60.0;
  t.body_names = {"a, \"b\"", "c"};
  for (std::int64_t s = 0; s < samples; ++s) {
    t.recorded.push_back(s);
    for (int b = 0; b < 2; ++b) {
      dropcheck::BodyState st;
      st.position = dropcheck::Vec3(s * 0.1, -9.81 * s * s / 7.0, b ? 1e300 : -5e-324);
      st.velocity = dropcheck::Vec3(1.0 / (s + 1), 0.0, -static_cast<double>(s));
      t.states.push_back(st);
    }
  }
  t.steps = samples - 1;
  return t;
}

}  // namespace

TEST_CASE("the streamed CSV file is byte-identical to the CSV built whole before streaming",
          "[trajectory_io][atomic]") {
  ScratchDir d("csv-stream");
  for (std::int64_t samples : {0, 1, 7, 3000}) {  // 3000 samples: about 1 MB, 16 buffers
    const dropcheck::Trajectory t = long_run(samples);
    dropcheck::write_file_atomic(d.file("o.csv"), [&](std::ostream& o) {
      dropcheck::write_trajectories_csv(o, {&t, 1});
    });
    INFO(samples << " samples");
    const std::string got = slurp(d.file("o.csv"));
    CHECK(got == csv_as_before(t));
    CHECK(got == dropcheck::trajectories_to_csv({&t, 1}));
  }
  CHECK(fs::file_size(d.file("o.csv")) > 2 * 64 * 1024);
}

TEST_CASE("a streamed write that throws leaves the previous file and no temporary",
          "[trajectory_io][atomic]") {
  ScratchDir d("csv-stream-throw");
  dropcheck::write_file_atomic(d.file("o.csv"), "previous\n");
  const dropcheck::Trajectory t = long_run(3000);
  CHECK_THROWS_AS(dropcheck::write_file_atomic(d.file("o.csv"),
                                               [&](std::ostream& o) {
                                                 dropcheck::write_trajectories_csv(o, {&t, 1});
                                                 throw std::bad_alloc();
                                               }),
                  std::bad_alloc);
  CHECK(slurp(d.file("o.csv")) == "previous\n");
  std::size_t entries = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(d.path)) entries += e.exists();
  CHECK(entries == 1);
}
