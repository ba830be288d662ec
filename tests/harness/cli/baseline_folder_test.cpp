// A baseline folder is data from a stranger (docs/files.md, "Baseline folders"): `bless --out`,
// `bless --check --baselines` and `diff` never follow an entry out of the folder, never quote more
// than a short excerpt of what they cannot parse, and check a baseline against what it claims to
// be before comparing anything with it. Each case drives cli_main as a user would.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "../test_dirs.hpp"
#include "cli_driver.hpp"

using Catch::Matchers::Contains;
using dropcheck::testing::cli;
using dropcheck::testing::Result;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/free_fall.toml";
const std::string kGood = std::string(DROPCHECK_SOURCE_DIR) + "/tests/baselines/free_fall.ours.txt";
const std::string kSecret = "SECRET_TOKEN=hunter2";

// `text` with the first occurrence of `from` replaced by `to` (the case must change the file).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// A result set in `dir` holding the committed free_fall baseline of ours, possibly altered.
void put_baseline(const ScratchDir& dir, const std::string& text = slurp(kGood),
                  const std::string& name = "free_fall.ours.txt") {
  std::ofstream(dir.file(name), std::ios::binary) << text;
}

// `diff GOOD BAD` where BAD holds `text` as free_fall.ours.txt.
Result diff_with(const ScratchDir& good, const ScratchDir& bad, const std::string& text) {
  put_baseline(good);
  put_baseline(bad, text);
  return cli({"diff", good.path.string(), bad.path.string()});
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Nothing in a baseline folder is followed out of it.

TEST_CASE("bless --out refuses a link planted in its folder and writes nothing through it",
          "[cli][hostile][baselines]") {
  ScratchDir d("bf-bless-link"), elsewhere("bf-bless-link-elsewhere");
  const std::string notes = elsewhere.write("notes.txt", "my notes\n");
  fs::create_directories(d.path / "out");
  fs::create_symlink(notes, d.path / "out" / "free_fall.ours.txt");
  const Result r = cli({"bless", kScene, "--engine", "ours", "--out", d.file("out")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("free_fall.ours.txt") && Contains("symbolic link"));
  CHECK(slurp(notes) == "my notes\n");
  CHECK(fs::is_symlink(d.path / "out" / "free_fall.ours.txt"));
}

TEST_CASE("bless --out refuses a dangling link, a folder and a FIFO where a baseline goes",
          "[cli][hostile][baselines]") {
  ScratchDir d("bf-bless-kinds");
  const fs::path out = d.path / "out";
  fs::create_directories(out);
  SECTION("a dangling link") {
    fs::create_symlink(d.path / "nowhere" / "x.txt", out / "free_fall.ours.txt");
  }
  SECTION("a folder") {
    fs::create_directories(out / "free_fall.ours.txt");
  }
  SECTION("a FIFO") {
    REQUIRE(::mkfifo((out / "free_fall.ours.txt").c_str(), 0600) == 0);
  }
  const Result r = cli({"bless", kScene, "--engine", "ours", "--out", out.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("free_fall.ours.txt"));
  CHECK(!fs::exists(d.path / "nowhere"));
  CHECK(!fs::is_regular_file(fs::symlink_status(out / "free_fall.ours.txt")));
}

TEST_CASE("diff and bless --check never read through a link in a baseline folder",
          "[cli][hostile][baselines]") {
  ScratchDir a("bf-link-a"), b("bf-link-b"), home("bf-link-home");
  const std::string secret = home.write("credentials", kSecret + "\n");
  put_baseline(a);
  fs::create_symlink(secret, b.path / "free_fall.ours.txt");
  const Result diff = cli({"diff", a.path.string(), b.path.string()});
  CHECK(diff.code == 2);
  CHECK_THAT(diff.err, Contains("free_fall.ours.txt") && Contains("symbolic link"));
  CHECK(diff.err.find("hunter2") == std::string::npos);
  const Result check = cli({"bless", "--check", kScene, "--engine", "ours", "--tier", "tolerance",
                            "--baselines", b.path.string()});
  CHECK(check.code == 2);
  CHECK_THAT(check.err, Contains("symbolic link"));
  CHECK(check.err.find("hunter2") == std::string::npos);
  CHECK(check.out.find("hunter2") == std::string::npos);
}

TEST_CASE("a regular file that is not a baseline is named, never quoted",
          "[cli][hostile][baselines]") {
  ScratchDir a("bf-notbaseline-a"), b("bf-notbaseline-b");
  const Result r = diff_with(a, b, kSecret + "\nscene free_fall\n");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("is not a baseline"));
  CHECK(r.err.find("hunter2") == std::string::npos);
}

TEST_CASE("a 40 MB baseline line comes back as a short excerpt", "[cli][hostile][baselines]") {
  ScratchDir a("bf-huge-a"), b("bf-huge-b");
  const std::string huge(40u << 20, '7');
  const Result r = diff_with(
      a, b, replaced(slurp(kGood), "sample 0 cube 0 10", "sample 0 cube 0 " + huge + "x"));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("not a number") && Contains("bytes)"));
  CHECK(r.err.size() < 400);
}

TEST_CASE("bless --check with a --baselines folder that does not exist is a usage error",
          "[cli][hostile][baselines]") {
  ScratchDir d("bf-missing");
  const Result r = cli(
      {"bless", "--check", kScene, "--engine", "ours", "--baselines", d.file("no-such-folder")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("no-such-folder") && Contains("does not exist"));
}

// ---------------------------------------------------------------------------------------------
// A baseline is checked against what it claims to be.

TEST_CASE("bless --check refuses a baseline of another scene, engine or scalar",
          "[cli][hostile][baselines]") {
  ScratchDir b("bf-claims");
  std::string field, text = slurp(kGood);
  SECTION("another scene") {
    field = "scene";
    text = replaced(text, "scene free_fall\n", "scene wind\n");
  }
  SECTION("another engine") {
    field = "engine";
    text = replaced(text, "engine ours\n", "engine ours-f64\n");
  }
  SECTION("another scalar") {
    field = "scalar";
    text = replaced(text, "scalar f32\n", "scalar f64\n");
  }
  SECTION("another step size") {
    field = "dt";
    text = replaced(text, "dt 1/60 0.016666666666666666\n", "dt 1/30 0.033333333333333333\n");
  }
  put_baseline(b, text);
  const Result r = cli({"bless", "--check", kScene, "--engine", "ours", "--tier", "tolerance",
                        "--baselines", b.path.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("free_fall.ours.txt: " + field + ":"));
}

TEST_CASE("diff refuses a baseline whose header contradicts itself or its file name",
          "[cli][hostile][baselines]") {
  ScratchDir a("bf-self-a"), b("bf-self-b");
  const std::string good = slurp(kGood);
  std::string text, field;
  SECTION("record_every 0") {
    text = replaced(good, "record_every 10\n", "record_every 0\n"), field = "record_every";
  }
  SECTION("a step of 1/0") {
    text = replaced(good, "dt 1/60 0.016666666666666666\n", "dt 1/0 inf\n"), field = "dt";
  }
  SECTION("step text and seconds that disagree") {
    text = replaced(good, "dt 1/60 0.016666666666666666\n", "dt 1/60 0.5\n"), field = "dt";
  }
  SECTION("a step count the samples contradict") {
    text = replaced(good, "steps 60\n", "steps 600\n"), field = "steps";
  }
  SECTION("samples at steps record_every does not keep") {
    text = replaced(good, "record_every 10\n", "record_every 7\n"), field = "sample";
  }
  SECTION("a file named for another scene") {
    put_baseline(a, good, "wind.ours.txt");
    put_baseline(b, good, "wind.ours.txt");
    const Result r = cli({"diff", a.path.string(), b.path.string()});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("wind.ours.txt") && Contains("free_fall.ours.txt"));
    return;
  }
  const Result r = diff_with(a, b, text);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains(field + ":"));
}

TEST_CASE("diff shows a NaN where one appears, never 'identical, 0 m'",
          "[cli][hostile][baselines]") {
  ScratchDir a("bf-nan-a"), b("bf-nan-b");
  // The hash line is left as it was: only the stored samples say what changed.
  const Result r =
      diff_with(a, b, replaced(slurp(kGood), "sample 0 cube 0 10 0", "sample 0 cube 0 nan 0"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("cube.y: 10 -> nan"));
  CHECK(r.out.find("| identical |") == std::string::npos);
  CHECK_THAT(r.out, Contains("1 of 1 scene/engine runs moved"));
}

TEST_CASE("diff of two equal result sets is still identical", "[cli][baselines]") {
  ScratchDir a("bf-same-a"), b("bf-same-b");
  const Result r = diff_with(a, b, slurp(kGood));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("| identical |") && Contains("0 of 1 scene/engine runs moved"));
}
