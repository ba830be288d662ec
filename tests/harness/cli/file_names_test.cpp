// Files as a user expects them: a report folder gets the mode any new folder gets, and a scene
// with a name as long as a file name may be is reported and blessed under shortened, unique file
// names (docs/files.md). Each case drives cli_main as a user would.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "../test_dirs.hpp"
#include "cli_driver.hpp"
#include "tests/scene_texts.hpp"

using Catch::Matchers::Contains;
using dropcheck::testing::body_text;
using dropcheck::testing::cli;
using dropcheck::testing::kEarth;
using dropcheck::testing::kZero;
using dropcheck::testing::Result;
using dropcheck::testing::scene_head;
using dropcheck::testing::ScratchDir;
namespace fs = std::filesystem;

namespace {

// Sets the umask for its lifetime.
struct Umask {
  mode_t previous;
  explicit Umask(mode_t mask) : previous(::umask(mask)) {}
  ~Umask() { ::umask(previous); }
};

mode_t mode_of(const fs::path& p) {
  struct stat st {};
  REQUIRE(::stat(p.c_str(), &st) == 0);
  return st.st_mode & 07777;
}

// A one-second free fall named `name`, in `dir`/`file`.
std::string fall_scene(const ScratchDir& dir, const std::string& file, const std::string& name) {
  return dir.write(file, "name = \"" + name + "\"\n" + scene_head("1.0", "1/60", kEarth) +
                             body_text("cube", "[0.0, 10.0, 0.0]", kZero));
}

}  // namespace

TEST_CASE("a new report folder gets 0777 less the umask, a replaced one keeps its mode",
          "[cli][files]") {
  ScratchDir d("names-mode");
  const std::string scene = fall_scene(d, "s.toml", "fall");
  const std::string out = d.file("report");
  {
    const Umask mask(027);
    REQUIRE(cli({"report", scene, "--out", out, "--engine", "ours", "--no-timing"}).code == 0);
    CHECK(mode_of(out) == 0750);
  }
  {
    const Umask mask(022);
    fs::remove_all(out);
    REQUIRE(cli({"report", scene, "--out", out, "--engine", "ours", "--no-timing"}).code == 0);
    CHECK(mode_of(out) == 0755);
    REQUIRE(::chmod(out.c_str(), 0700) == 0);
    REQUIRE(cli({"report", scene, "--out", out, "--engine", "ours", "--no-timing"}).code == 0);
    CHECK(mode_of(out) == 0700);
  }
}

TEST_CASE("scenes with 255-byte names are reported and blessed under short, unique file names",
          "[cli][files]") {
  ScratchDir d("names-long");
  const std::string a(255, 'a');
  std::string b = a;
  b.back() = 'b';
  const std::string sa = fall_scene(d, "a.toml", a), sb = fall_scene(d, "b.toml", b);
  const Result report =
      cli({"report", sa, sb, "--out", d.file("report"), "--engine", "ours", "--no-timing"});
  CHECK(report.code == 0);
  CHECK(fs::exists(d.path / "report" / "README.md"));
  const Result bless = cli({"bless", sa, sb, "--engine", "ours", "--out", d.file("set")});
  CHECK(bless.code == 0);
  int baselines = 0;
  for (const auto& e : fs::directory_iterator(d.path / "set")) {
    CHECK(e.path().filename().string().size() <= 120);
    ++baselines;
  }
  CHECK(baselines == 2);
  // The set reads back: diff finds each file under the name its header gives.
  const Result diff = cli({"diff", d.file("set"), d.file("set")});
  CHECK(diff.code == 0);
  CHECK_THAT(diff.out, Contains("0 of 2 scene/engine runs moved"));
}
