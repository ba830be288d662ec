// Hostile input to the dropcheck command line (harness/cli/*, harness/core/atomic_file,
// output_dir, output_plan, signal_cleanup, harness/guard/bless): every case drives cli_main with an
// argument vector and scratch folders and checks the exit code, the message, and what is (not)
// left on disk. The rules are in docs/files.md.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_dirs.hpp"
#include "cli_driver.hpp"
#include "harness/cli/cli.hpp"
#include "harness/io/json_text.hpp"
#include "harness/io/output_dir.hpp"
#include "harness/process/signal_cleanup.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;
namespace fs = std::filesystem;

namespace {

using dropcheck::testing::cli;
using dropcheck::testing::Result;

void put(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A tiny free-fall scene (10 steps; `name` as given, TOML-escaped by the caller).
std::string scene_text(const std::string& name = "tiny", const std::string& extra = "") {
  return "name = \"" + name +
         "\"\nduration = 0.5\ntimestep = \"1/20\"\ntimesteps = [\"1/10\", \"1/20\"]\n" +
         "[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\nname = \"c\"\nposition = [0.0, 10.0, "
         "0.0]\n" +
         extra;
}

std::string hostile_scene(const ScratchDir& d, const std::string& file = "tiny.toml",
                          const std::string& name = "tiny") {
  put(d.file(file), scene_text(name));
  return d.file(file);
}

// Every name in `dir` (hidden ones too), sorted.
std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    out.insert(e.path().filename().string());
  return out;
}

// Every file under `dir`, recursively, as relative paths.
std::set<std::string> tree(const fs::path& dir) {
  std::set<std::string> out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    out.insert(fs::relative(e.path(), dir).string());
  return out;
}

// A user's folder: a README.md and two SVGs dropcheck did not write.
void user_folder(const fs::path& dir) {
  put((dir / "README.md").string(), "# My notes\n");
  put((dir / "a.svg").string(), "<svg/>");
  put((dir / "b.svg").string(), "<svg/>");
}

// `run` on the tiny scene with ours-f64 into `extra` outputs.
Result run_tiny(const std::string& scene_file, std::vector<std::string> extra) {
  std::vector<std::string> argv{"run", scene_file, "--engine", "ours-f64"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return cli(argv);
}

// fork() with SIGTERM at its default in the child (Catch2 installs its own handler, which would
// print a test report from the child): blocked across the fork so that no early signal reaches
// Catch2's.
pid_t fork_plain() {
  sigset_t term, old;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  ::sigprocmask(SIG_BLOCK, &term, &old);
  const pid_t pid = ::fork();
  if (pid == 0) ::signal(SIGTERM, SIG_DFL);
  ::sigprocmask(SIG_SETMASK, &old, nullptr);
  return pid;
}

// `bless` of two scenes into d/set: a.toml named `a` and b.toml named `b` (TOML-escaped by the
// caller).
Result bless_two(const ScratchDir& d, const std::string& a, const std::string& b) {
  put(d.file("a.toml"), scene_text(a));
  put(d.file("b.toml"), scene_text(b));
  return cli({"bless", d.file("a.toml"), d.file("b.toml"), "--engine", "ours-f64", "--out",
              d.file("set")});
}

// Two files in `d` that cannot be read, each with the reason given: missingEXT (absent) and dirEXT
// (made a folder here).
std::vector<std::pair<std::string, std::string>> unreadable_files(const ScratchDir& d,
                                                                  const std::string& ext) {
  fs::create_directories(d.path / ("dir" + ext));
  return {{d.file("missing" + ext), "No such file or directory"},
          {d.file("dir" + ext), "it is a directory"}};
}

// The engines ran when the summary's header was printed.
bool engines_ran(const Result& r) {
  return r.out.find("engine    body") != std::string::npos;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The command line (CLI11): --help everywhere, strays and empty values refused, naming the option.

TEST_CASE("dropcheck --help lists every command on stdout and exits 0", "[cli][hostile]") {
  const Result r = cli({"--help"});
  CHECK(r.code == 0);
  for (const char* c : {"engines", "run", "bless", "diff", "check", "report", "stability"})
    CHECK_THAT(r.out, Contains(std::string("dropcheck ") + c));
  CHECK_THAT(r.out, Contains("COMMAND --help"));
}

TEST_CASE("every command answers --help with its options on stdout and exit 0", "[cli][hostile]") {
  const std::vector<std::pair<std::string, std::string>> commands{{"engines", "dropcheck engines"},
                                                                  {"run", "--csv"},
                                                                  {"bless", "--baselines"},
                                                                  {"diff", "--out"},
                                                                  {"check", "--engine"},
                                                                  {"report", "--no-timing"},
                                                                  {"stability", "--json"}};
  for (const auto& [command, option] : commands) {
    const Result r = cli({command, "--help"});
    INFO(command);
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Contains(option) && Contains("dropcheck " + command));
    CHECK(r.err.empty());
  }
}

TEST_CASE("-h is --help too, even after other arguments", "[cli][hostile]") {
  const Result r = cli({"run", "no-such.toml", "-h"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("--dt"));
}

TEST_CASE("engines with a stray argument is refused naming it", "[cli][hostile]") {
  const Result r = cli({"engines", "foo"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("'foo'") && Contains("takes no arguments"));
  CHECK(r.out.empty());
}

TEST_CASE("run --csv '' names --csv and writes nothing", "[cli][hostile]") {
  ScratchDir d("hostile-csv-empty");
  const std::string s = hostile_scene(d);
  const Result r = run_tiny(s, {"--csv", ""});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--csv"));
  CHECK(names(d.path) == std::set<std::string>{"tiny.toml"});
}

TEST_CASE(
    "a bad option value, a repeated, unknown or valueless option is refused naming it, before any "
    "engine runs",
    "[cli][hostile]") {
  ScratchDir d("hostile-option-refused");
  const std::string s = hostile_scene(d);
  // Each row: what it is, the command line and what the error says.
  struct Case {
    std::string what;
    std::vector<std::string> argv, says;
  };
  const std::vector<Case> cases{
      {"run --dt '' is refused naming --dt before any engine runs",
       {"run", s, "--engine", "ours-f64", "--dt", ""},
       {"--dt", "empty"}},
      {"stability --json '' names --json",
       {"stability", s, "--engine", "ours-f64", "--json", ""},
       {"--json"}},
      {"report --out '' names --out", {"report", s, "--engine", "ours", "--out", ""}, {"--out"}},
      {"a single-valued option given twice is refused rather than silently taking one",
       {"run", s, "--engine", "ours-f64", "--dt", "1/20", "--dt", "1/10"},
       {"--dt", "2 times"}},
      {"a single-dash word is an unknown option, not a scene file",
       {"run", s, "--engine", "ours-f64", "-x"},
       {"-x", "unknown option"}},
      {"a missing value names the option",
       {"run", s, "--engine", "ours-f64", "--engine"},
       {"--engine", "expects a value"}},
      {"check without a scene file is refused",
       {"check", "--engine", "ours"},
       {"one or more PATHs"}},
      {"report --out . is refused",
       {"report", s, "--engine", "ours", "--no-timing", "--out", "."},
       {"--out"}},
      {"report --out /proc/x is refused before any engine runs",
       {"report", s, "--engine", "ours", "--no-timing", "--out", "/proc/dropcheck-x"},
       {"--out"}},
      {"run --json /proc/x is refused before any engine runs",
       {"run", s, "--engine", "ours-f64", "--json", "/proc/dropcheck-x.json"},
       {"--json", "cannot write"}},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    const Result r = cli(c.argv);
    CHECK(r.code == 2);
    for (const std::string& text : c.says) CHECK_THAT(r.err, Contains(text));
    CHECK_THAT(r.err, !Contains("[1/1]"));  // no progress line: nothing was evaluated
    CHECK_FALSE(engines_ran(r));
  }
}

TEST_CASE("diff with one or three folders is refused", "[cli][hostile]") {
  ScratchDir d("hostile-diff-count");
  CHECK(cli({"diff", d.path.string()}).code == 2);
  const Result three = cli({"diff", d.path.string(), d.path.string(), d.path.string()});
  CHECK(three.code == 2);
  CHECK_THAT(three.err, Contains("exactly two"));
}

TEST_CASE("a file named like an option is reachable after --", "[cli][hostile]") {
  ScratchDir d("hostile-dashdash");
  put(d.file("-x.toml"), scene_text());
  const Result r = cli({"check", "--engine", "ours-f64", "--", d.file("-x.toml")});
  CHECK(r.code != 2);
  CHECK_THAT(r.out, Contains("checks passed"));
}

// ---------------------------------------------------------------------------------------------
// An output is never an input, and two outputs never share a path.

TEST_CASE(
    "run with an output that is its own scene, however spelled or linked, is refused before "
    "any engine runs and the scene is untouched",
    "[cli][hostile]") {
  // Each row: what it is, the option, how its path is made from the scratch folder (the scene is
  // tiny.toml there) and what the error says.
  struct Case {
    std::string what, option;
    std::function<std::string(const ScratchDir&)> output;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases{
      {"run S --csv S",
       "--csv",
       [](const ScratchDir& d) { return d.file("tiny.toml"); },
       {"--csv", "input"}},
      {"run S --json S, S spelled differently",
       "--json",
       [](const ScratchDir& d) {
         return (d.path / "." / ".." / d.path.filename() / "tiny.toml").string();
       },
       {"--json"}},
      {"run --csv through a symbolic link to the scene",
       "--csv",
       [](const ScratchDir& d) {
         fs::create_symlink(d.file("tiny.toml"), d.file("link.csv"));
         return d.file("link.csv");
       },
       {}},
      {"run --csv onto a hard link of the scene",
       "--csv",
       [](const ScratchDir& d) {
         fs::create_hard_link(d.file("tiny.toml"), d.file("same.csv"));
         return d.file("same.csv");
       },
       {}},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    ScratchDir d("hostile-output-is-input");
    const std::string s = hostile_scene(d);
    const std::string before = slurp(s);
    const Result r = run_tiny(s, {c.option, c.output(d)});
    CHECK(r.code == 2);
    for (const std::string& text : c.says) CHECK_THAT(r.err, Contains(text));
    CHECK(slurp(s) == before);
    CHECK_FALSE(engines_ran(r));
  }
}

TEST_CASE("run --csv X --json X is refused before any work and X is not created",
          "[cli][hostile]") {
  ScratchDir d("hostile-two-outputs");
  const std::string s = hostile_scene(d);
  const Result r = run_tiny(s, {"--csv", d.file("x"), "--json", d.file("x")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--json") && Contains("--csv"));
  CHECK_FALSE(fs::exists(d.file("x")));
  CHECK_FALSE(engines_ran(r));
}

TEST_CASE("stability S --json S is refused and the scene is untouched", "[cli][hostile]") {
  ScratchDir d("hostile-stability-input");
  const std::string s = hostile_scene(d);
  const std::string before = slurp(s);
  const Result r = cli({"stability", s, "--engine", "ours-f64", "--json", s});
  CHECK(r.code == 2);
  CHECK(slurp(s) == before);
}

TEST_CASE("check DIR --junit DIR/x.xml and --json S are refused before any check runs",
          "[cli][hostile]") {
  ScratchDir d("hostile-check-input");
  const std::string s = hostile_scene(d);
  const std::string before = slurp(s);
  Result r = cli({"check", s, "--engine", "ours-f64", "--json", s});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--json"));
  CHECK(slurp(s) == before);
  r = cli({"check", d.path.string(), "--engine", "ours-f64", "--junit", d.file("v.xml")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--junit"));
  CHECK_FALSE(fs::exists(d.file("v.xml")));
  CHECK(r.out.empty());  // no check ran
}

TEST_CASE("diff A B --out A/summary.md is refused: A is an input", "[cli][hostile]") {
  ScratchDir a("hostile-diff-in-a"), b("hostile-diff-in-b");
  const std::string s = hostile_scene(a, "s.toml");
  REQUIRE(cli({"bless", s, "--engine", "ours-f64", "--out", (a.path / "set").string()}).code == 0);
  REQUIRE(cli({"bless", s, "--engine", "ours-f64", "--out", (b.path / "set").string()}).code == 0);
  const Result r = cli({"diff", (a.path / "set").string(), (b.path / "set").string(), "--out",
                        (a.path / "set" / "summary.md").string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--out"));
  CHECK_FALSE(fs::exists(a.path / "set" / "summary.md"));
}

// ---------------------------------------------------------------------------------------------
// Only regular files are replaced; a symbolic link is written through.

TEST_CASE("run --csv onto an existing folder is refused and the folder is untouched",
          "[cli][hostile]") {
  ScratchDir d("hostile-csv-dir");
  fs::create_directories(d.path / "out" / "keep");
  const Result r = run_tiny(hostile_scene(d), {"--csv", d.file("out")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("directory"));
  CHECK(fs::is_directory(d.path / "out" / "keep"));
}

TEST_CASE("run --csv /dev/null is refused: a device is never replaced", "[cli][hostile]") {
  ScratchDir d("hostile-devnull");
  const Result r = run_tiny(hostile_scene(d), {"--csv", "/dev/null"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("character device"));
  struct stat st {};
  REQUIRE(::stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
}

TEST_CASE("run --csv onto a FIFO is refused without blocking", "[cli][hostile]") {
  ScratchDir d("hostile-fifo");
  REQUIRE(::mkfifo(d.file("pipe").c_str(), 0600) == 0);
  const Result r = run_tiny(hostile_scene(d), {"--csv", d.file("pipe")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("FIFO"));
  struct stat st {};
  REQUIRE(::lstat(d.file("pipe").c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
}

TEST_CASE("run --csv through a symbolic link writes the linked file and keeps the link",
          "[cli][hostile]") {
  ScratchDir d("hostile-link-through");
  put(d.file("real.csv"), "old");
  fs::create_symlink("real.csv", d.file("link.csv"));  // relative, resolved from the link's folder
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("link.csv")}).code == 0);
  CHECK(fs::is_symlink(d.file("link.csv")));
  CHECK_THAT(slurp(d.file("real.csv")), StartsWith("engine,dt,step"));
}

TEST_CASE("run --csv through a dangling link creates the file it names", "[cli][hostile]") {
  ScratchDir d("hostile-link-dangling");
  fs::create_symlink(d.file("made.csv"), d.file("link.csv"));
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("link.csv")}).code == 0);
  CHECK(fs::is_symlink(d.file("link.csv")));
  CHECK_THAT(slurp(d.file("made.csv")), StartsWith("engine,dt,step"));
}

TEST_CASE("run --csv through a link to a device is refused", "[cli][hostile]") {
  ScratchDir d("hostile-link-dev");
  fs::create_symlink("/dev/null", d.file("link.csv"));
  const Result r = run_tiny(hostile_scene(d), {"--csv", d.file("link.csv")});
  CHECK(r.code == 2);
  CHECK(fs::is_symlink(d.file("link.csv")));
}

TEST_CASE("run --csv on a symbolic link loop is refused", "[cli][hostile]") {
  ScratchDir d("hostile-link-loop");
  fs::create_symlink(d.file("b"), d.file("a"));
  fs::create_symlink(d.file("a"), d.file("b"));
  const Result r = run_tiny(hostile_scene(d), {"--csv", d.file("a")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("symbolic links"));
}

TEST_CASE("a user's own OUT.tmp survives a run writing OUT", "[cli][hostile]") {
  ScratchDir d("hostile-user-tmp");
  put(d.file("out.csv.tmp"), "mine");
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("out.csv")}).code == 0);
  CHECK(slurp(d.file("out.csv.tmp")) == "mine");
}

TEST_CASE("a run leaves no temporary file beside its outputs", "[cli][hostile]") {
  ScratchDir d("hostile-no-tmp");
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("o.csv"), "--json", d.file("o.json")}).code ==
          0);
  CHECK(names(d.path) == std::set<std::string>{"o.csv", "o.json", "tiny.toml"});
}

TEST_CASE("a replaced output keeps its permissions", "[cli][hostile]") {
  ScratchDir d("hostile-mode");
  put(d.file("o.csv"), "old");
  fs::permissions(d.file("o.csv"), fs::perms::owner_read | fs::perms::owner_write);
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("o.csv")}).code == 0);
  CHECK(fs::status(d.file("o.csv")).permissions() ==
        (fs::perms::owner_read | fs::perms::owner_write));
}

// ---------------------------------------------------------------------------------------------
// Every output location is checked before any engine runs.

TEST_CASE("run --csv under a regular file is refused before any engine runs", "[cli][hostile]") {
  ScratchDir d("hostile-under-file");
  put(d.file("file"), "x");
  const Result r = run_tiny(hostile_scene(d), {"--csv", d.file("file/sub/out.csv")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--csv") && Contains("not a folder"));
  CHECK_FALSE(engines_ran(r));
  CHECK(slurp(d.file("file")) == "x");
}

TEST_CASE("run --csv naming a folder (trailing slash, '.') is refused", "[cli][hostile]") {
  ScratchDir d("hostile-csv-slash");
  const std::string s = hostile_scene(d);
  const Result slash = run_tiny(s, {"--csv", d.file("newdir") + "/"});
  CHECK(slash.code == 2);
  CHECK_THAT(slash.err, Contains("folder"));
  CHECK(run_tiny(s, {"--csv", "."}).code == 2);
  CHECK_FALSE(fs::exists(d.file("newdir")));
}

TEST_CASE("run --csv into folders that do not exist yet creates them", "[cli][hostile]") {
  ScratchDir d("hostile-csv-mkdir");
  REQUIRE(run_tiny(hostile_scene(d), {"--csv", d.file("a/b/o.csv")}).code == 0);
  CHECK_THAT(slurp(d.file("a/b/o.csv")), StartsWith("engine,dt"));
}

TEST_CASE("report --out under a regular file, or onto one, is refused", "[cli][hostile]") {
  ScratchDir d("hostile-report-file");
  const std::string s = hostile_scene(d);
  put(d.file("file"), "x");
  CHECK(cli({"report", s, "--engine", "ours", "--out", d.file("file/rep")}).code == 2);
  const Result onto = cli({"report", s, "--engine", "ours", "--out", d.file("file")});
  CHECK(onto.code == 2);
  CHECK_THAT(onto.err, Contains("not a folder"));
  CHECK(slurp(d.file("file")) == "x");
}

TEST_CASE("report --out a folder holding its own input scene is refused", "[cli][hostile]") {
  ScratchDir d("hostile-report-holds-input");
  const std::string s = hostile_scene(d, "rep/tiny.toml");
  const Result r = cli({"report", s, "--engine", "ours", "--out", d.file("rep")});
  CHECK(r.code == 2);
  CHECK(fs::exists(s));
}

TEST_CASE("bless --out a regular file or /proc is refused before any engine runs",
          "[cli][hostile]") {
  ScratchDir d("hostile-bless-out");
  const std::string s = hostile_scene(d);
  put(d.file("file"), "x");
  CHECK(cli({"bless", s, "--engine", "ours-f64", "--out", d.file("file")}).code == 2);
  CHECK(cli({"bless", s, "--engine", "ours-f64", "--out", "/proc/dropcheck-x"}).code == 2);
  CHECK(slurp(d.file("file")) == "x");
}

// ---------------------------------------------------------------------------------------------
// The report folder: only a folder dropcheck wrote is replaced.

TEST_CASE("report --out a user's folder of README.md and SVGs is refused and left as it was",
          "[cli][hostile]") {
  ScratchDir d("hostile-report-user");
  const std::string s = hostile_scene(d);
  user_folder(d.path / "mine");
  const std::set<std::string> before = tree(d.path / "mine");
  const Result r = cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("mine")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("README.md") && Contains("did not write"));
  CHECK(tree(d.path / "mine") == before);
  CHECK(slurp(d.file("mine/README.md")) == "# My notes\n");
}

TEST_CASE("a report folder carries a manifest and is replaced by the next report",
          "[cli][hostile]") {
  ScratchDir d("hostile-report-manifest");
  const std::string s = hostile_scene(d);
  REQUIRE(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 0);
  const std::string manifest = slurp(d.file("rep/.dropcheck-manifest"));
  CHECK_THAT(manifest, Contains("\nREADME.md\n"));
  for (const std::string& f : names(d.path / "rep"))
    if (f != ".dropcheck-manifest") CHECK_THAT(manifest, Contains("\n" + f + "\n"));
  REQUIRE(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 0);
  CHECK(names(d.path) == std::set<std::string>{"rep", "tiny.toml"});  // no staging, no backup
}

TEST_CASE("a report folder with a file its manifest does not list is refused", "[cli][hostile]") {
  ScratchDir d("hostile-report-unlisted");
  const std::string s = hostile_scene(d);
  REQUIRE(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 0);
  put(d.file("rep/notes.txt"), "mine");
  const Result r = cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("notes.txt"));
  CHECK(slurp(d.file("rep/notes.txt")) == "mine");
}

TEST_CASE("a report folder holding a subfolder is refused", "[cli][hostile]") {
  ScratchDir d("hostile-report-subdir");
  const std::string s = hostile_scene(d);
  REQUIRE(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 0);
  fs::create_directories(d.path / "rep" / "keep");
  CHECK(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 2);
  CHECK(fs::is_directory(d.path / "rep" / "keep"));
}

TEST_CASE("a report written before manifests is adopted only when its README names every SVG",
          "[cli][hostile]") {
  ScratchDir d("hostile-report-legacy");
  put(d.file("old/README.md"), "# dropcheck comparison report\n\n![x](x-trajectory.svg)\n");
  put(d.file("old/x-trajectory.svg"), "<svg/>");
  CHECK_NOTHROW(dropcheck::check_replaceable(d.file("old")));
  put(d.file("old/y.svg"), "<svg/>");  // not named by the README: a user's
  CHECK_THROWS_WITH(dropcheck::check_replaceable(d.file("old")), Contains("y.svg"));
}

TEST_CASE("report --out a symbolic link to a user's folder is refused", "[cli][hostile]") {
  ScratchDir d("hostile-report-link");
  const std::string s = hostile_scene(d);
  user_folder(d.path / "mine");
  fs::create_directory_symlink(d.path / "mine", d.path / "rep");
  CHECK(cli({"report", s, "--engine", "ours", "--out", d.file("rep")}).code == 2);
  CHECK(slurp(d.file("mine/README.md")) == "# My notes\n");
}

TEST_CASE("the committed reports/ folder is one dropcheck may replace", "[cli][hostile]") {
  CHECK_NOTHROW(dropcheck::check_replaceable(DROPCHECK_SOURCE_DIR "/reports"));
}

// ---------------------------------------------------------------------------------------------
// Signals and concurrent runs.

TEST_CASE("SIGTERM removes a registered temporary file and staging folder, then kills",
          "[cli][hostile]") {
  ScratchDir d("hostile-signal");
  put(d.file(".o.csv.tmp-abc"), "partial");
  put(d.file(".rep.staging-abc/README.md"), "partial");
  put(d.file(".rep.staging-abc/a.svg"), "partial");
  const pid_t pid = fork_plain();
  if (pid == 0) {
    dropcheck::CleanupOnSignal file(d.file(".o.csv.tmp-abc"), false);
    dropcheck::CleanupOnSignal folder(d.file(".rep.staging-abc"), true);
    ::raise(SIGTERM);
    ::_exit(0);  // not reached
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(names(d.path).empty());
}

TEST_CASE("a report killed at any moment leaves the previous report whole and nothing beside it",
          "[cli][hostile]") {
  ScratchDir d("hostile-report-kill");
  const std::string s = hostile_scene(d);
  REQUIRE(cli({"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}).code == 0);
  const std::set<std::string> complete = tree(d.path / "rep");
  for (int delay_us : {0, 500, 1000, 2000, 4000, 8000, 16000, 32000}) {
    const pid_t pid = fork_plain();
    if (pid == 0) {
      std::ostringstream out, err;
      ::_exit(dropcheck::cli_main(
          {"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}, out, err));
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us));
    ::kill(pid, SIGTERM);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    INFO("killed after " << delay_us << " us");
    CHECK(names(d.path) == std::set<std::string>{"rep", "tiny.toml"});
    CHECK(tree(d.path / "rep") == complete);
  }
}

TEST_CASE("two runs writing the same CSV at once leave one run's complete output and both exit 0",
          "[cli][hostile]") {
  ScratchDir d("hostile-concurrent-csv");
  const std::string s = hostile_scene(d);
  REQUIRE(run_tiny(s, {"--dt", "1/10", "--csv", d.file("ref10.csv")}).code == 0);
  REQUIRE(run_tiny(s, {"--dt", "1/20", "--csv", d.file("ref20.csv")}).code == 0);
  for (int round = 0; round < 5; ++round) {
    pid_t pids[2];
    for (int i = 0; i < 2; ++i) {
      pids[i] = fork_plain();
      if (pids[i] == 0) {
        std::ostringstream out, err;
        ::_exit(dropcheck::cli_main({"run", s, "--engine", "ours-f64", "--dt", i ? "1/20" : "1/10",
                                     "--csv", d.file("o.csv")},
                                    out, err));
      }
    }
    for (pid_t pid : pids) {
      int status = 0;
      REQUIRE(::waitpid(pid, &status, 0) == pid);
      CHECK(WIFEXITED(status));
      CHECK(WEXITSTATUS(status) == 0);
    }
    const std::string got = slurp(d.file("o.csv"));
    CHECK((got == slurp(d.file("ref10.csv")) || got == slurp(d.file("ref20.csv"))));
  }
  CHECK(names(d.path) == std::set<std::string>{"o.csv", "ref10.csv", "ref20.csv", "tiny.toml"});
}

TEST_CASE("two reports into one folder at once leave one complete report and both exit 0",
          "[cli][hostile]") {
  ScratchDir d("hostile-concurrent-report");
  const std::string s = hostile_scene(d);
  for (int round = 0; round < 4; ++round) {
    pid_t pids[2];
    for (pid_t& pid : pids) {
      pid = fork_plain();
      if (pid == 0) {
        std::ostringstream out, err;
        ::_exit(dropcheck::cli_main(
            {"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}, out, err));
      }
    }
    for (pid_t pid : pids) {
      int status = 0;
      REQUIRE(::waitpid(pid, &status, 0) == pid);
      CHECK(WIFEXITED(status));
      CHECK(WEXITSTATUS(status) == 0);
    }
    CHECK(names(d.path) == std::set<std::string>{"rep", "tiny.toml"});
    std::set<std::string> listed;
    std::istringstream lines(slurp(d.file("rep/.dropcheck-manifest")));
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line[0] != '#') listed.insert(line);
    listed.insert(".dropcheck-manifest");
    CHECK(names(d.path / "rep") == listed);
  }
}

// ---------------------------------------------------------------------------------------------
// bless: scene names cannot leave --out or make two baselines collide.

TEST_CASE("bless a scene named ../x writes inside --out only", "[cli][hostile]") {
  ScratchDir d("hostile-bless-dotdot");
  put(d.file("s.toml"), scene_text("../x"));
  REQUIRE(cli({"bless", d.file("s.toml"), "--engine", "ours-f64", "--out", d.file("set")}).code ==
          0);
  CHECK(names(d.path) == std::set<std::string>{"s.toml", "set"});
  CHECK(names(d.path / "set") == std::set<std::string>{"_.._x.ours-f64.txt"});
}

TEST_CASE("bless a scene named with an absolute path writes inside --out only", "[cli][hostile]") {
  ScratchDir d("hostile-bless-abs");
  put(d.file("s.toml"), scene_text(d.file("escaped")));
  REQUIRE(cli({"bless", d.file("s.toml"), "--engine", "ours-f64", "--out", d.file("set")}).code ==
          0);
  CHECK_FALSE(fs::exists(d.file("escaped.ours-f64.txt")));
  CHECK(names(d.path / "set").size() == 1);
}

TEST_CASE("bless two scenes whose names map to one file is refused and writes nothing",
          "[cli][hostile]") {
  ScratchDir d("hostile-bless-collide");
  const Result r = bless_two(d, "a/b", "a_b");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("a/b") && Contains("a_b") && Contains("distinct names"));
  CHECK_FALSE(fs::exists(d.file("set")));
}

TEST_CASE("bless a scene name with a NUL byte neither truncates nor collides silently",
          "[cli][hostile]") {
  ScratchDir d("hostile-bless-nul");
  const Result r = bless_two(d, "a\\u0000b", "a_b");
  CHECK(r.code == 2);
  CHECK_FALSE(fs::exists(d.file("set/a.ours-f64.txt")));
}

TEST_CASE("bless --check finds a sanitised baseline and never looks outside --baselines",
          "[cli][hostile]") {
  ScratchDir d("hostile-bless-check-dotdot");
  put(d.file("s.toml"), scene_text("../x"));
  REQUIRE(cli({"bless", d.file("s.toml"), "--engine", "ours-f64", "--out", d.file("set")}).code ==
          0);
  const Result r = cli({"bless", "--check", d.file("s.toml"), "--engine", "ours-f64", "--tier",
                        "tolerance", "--baselines", d.file("set")});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("passed"));
}

// ---------------------------------------------------------------------------------------------
// Exit codes and messages tell the truth.

TEST_CASE("diff of two folders that hold no baselines exits 2", "[cli][hostile]") {
  ScratchDir a("hostile-diff-empty-a"), b("hostile-diff-empty-b");
  put(a.file("notes.md"), "x");
  const Result r = cli({"diff", a.path.string(), b.path.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("no baseline"));
}

TEST_CASE("diff of a binary .txt gives a sentence, not its bytes", "[cli][hostile]") {
  ScratchDir a("hostile-diff-binary-a"), b("hostile-diff-binary-b");
  put(a.file("x.txt"), std::string("\x7f"
                                   "ELF\x02\x01\x01\0\0\0\x1b[31mred",
                                   16));
  put(b.file("x.txt"), "scene x\n");
  const Result r = cli({"diff", a.path.string(), b.path.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("is not a baseline"));
  CHECK(r.err.find('\x1b') == std::string::npos);
  CHECK(r.err.find('\x7f') == std::string::npos);
}

TEST_CASE("a folder named like a baseline is a read error, not a missing key", "[cli][hostile]") {
  ScratchDir a("hostile-diff-dir-a"), b("hostile-diff-dir-b");
  fs::create_directories(a.path / "x.txt");
  put(b.file("y.txt"), "scene y\n");
  const Result r = cli({"diff", a.path.string(), b.path.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("cannot read") && Contains("directory"));
  CHECK(r.err.find("no 'scene'") == std::string::npos);
}

TEST_CASE("a force listing the same body twice is refused naming the entry", "[cli][hostile]") {
  ScratchDir d("hostile-force-twice");
  put(d.file("s.toml"),
      scene_text("twice", "[[force]]\nbodies = [\"c\", \"c\"]\nconstant = [1.0, 0.0, 0.0]\n"));
  const Result r = run_tiny(d.file("s.toml"), {});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("bodies[1]") && Contains("twice"));
}

TEST_CASE("an integer where a float is expected is accepted when exact", "[cli][hostile]") {
  ScratchDir d("hostile-integer");
  put(d.file("s.toml"),
      "duration = 1\ntimestep = \"1/10\"\n[world]\ngravity = [0, -10, 0]\n[[body]]\nname = \"c\"\n"
      "position = [0, 10, 0]\nmass = 2\n");
  const Result r = run_tiny(d.file("s.toml"), {});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("gravity (0, -10, 0)"));
}

TEST_CASE("numbers like 1e300 are printed whole in the run summary, not cut by a line buffer",
          "[cli][hostile]") {
  ScratchDir d("hostile-1e300");
  put(d.file("s.toml"),
      "duration = 0.5\ntimestep = \"1/10\"\n[world]\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = "
      "\"c\"\n"
      "position = [1e300, -1e300, 1e300]\n");
  const Result r = run_tiny(d.file("s.toml"), {});
  CHECK(r.code == 0);
  std::istringstream lines(r.out);
  std::string line, row;
  while (std::getline(lines, line))
    if (line.rfind("ours-f64", 0) == 0) row = line;
  CHECK(row.size() > 900);  // three 300-digit coordinates
  CHECK_THAT(row, Contains("  ok"));
}

TEST_CASE("checks and stability on overflowing numbers print no -nan", "[cli][hostile]") {
  ScratchDir d("hostile-nan");
  put(d.file("s.toml"),
      "duration = 1.0\ntimestep = \"1/60\"\n[world]\ngravity = [0.0, -1e300, 0.0]\n[[body]]\nname "
      "= \"c\"\n"
      "position = [0.0, 1e300, 0.0]\nvelocity = [1e300, 0.0, 0.0]\n");
  const Result check = cli({"check", d.file("s.toml"), "--engine", "ours-f64"});
  CHECK(check.out.find("nan") == std::string::npos);
  const Result stab = cli({"stability", d.file("s.toml"), "--engine", "ours-f64"});
  CHECK(stab.out.find("nan") == std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// JSON: every name is escaped by construction.

TEST_CASE("run --json with hostile scene and body names is valid JSON that reads the names back",
          "[cli][hostile]") {
  ScratchDir d("hostile-json-names");
  put(d.file("s.toml"),
      "name = \"q\\\"uote\\\\ \\u00e9\"\nduration = 0.5\ntimestep = "
      "\"1/10\"\n[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\n"
      "name = \"b}],\\\"x\\\":[{\"\nposition = [0.0, 1.0, 0.0]\n");
  REQUIRE(run_tiny(d.file("s.toml"), {"--json", d.file("o.json")}).code == 0);
  const nlohmann::json j = dropcheck::parse_json<nlohmann::json>(slurp(d.file("o.json")));
  CHECK(j["runs"][0]["scene"] == "q\"uote\\ \xc3\xa9");
  CHECK(j["runs"][0]["bodies"][0]["name"] == "b}],\"x\":[{");
}

TEST_CASE("stability --json with a hostile scene name is valid JSON", "[cli][hostile]") {
  ScratchDir d("hostile-stability-json");
  put(d.file("s.toml"),
      "name = \"\\\"}\"\nduration = 0.5\ntimestep = \"1/10\"\n[world]\ngravity = [0.0, "
      "-9.8, 0.0]\n[[body]]\nname = \"c\"\nposition = [0.0, 1.0, 0.0]\n");
  REQUIRE(cli({"stability", d.file("s.toml"), "--engine", "ours-f64", "--json", d.file("o.json")})
              .code == 0);
  const nlohmann::json j = dropcheck::parse_json<nlohmann::json>(slurp(d.file("o.json")));
  CHECK(j["scene"] == "\"}");
  CHECK(j["engines"][0]["engine"] == "ours-f64");
}

// ---------------------------------------------------------------------------------------------
// Reasons, labels and Ctrl-C during gnuplot.

TEST_CASE(
    "a scene that cannot be read is refused with the reason (missing file; folder; not a folder)",
    "[cli][hostile]") {
  ScratchDir d("hostile-scene-reason");
  const std::string s = hostile_scene(d);
  std::vector<std::pair<std::string, std::string>> cases = unreadable_files(d, ".toml");
  cases.push_back({s + "/x.toml", "Not a directory"});
  for (const auto& [file, reason] : cases)
    for (const char* command : {"run", "check", "stability"}) {
      const Result r = cli({command, file, "--engine", "ours-f64"});
      INFO(command << " " << file);
      CHECK(r.code == 2);
      // check takes a folder for the scene files in it: this one holds none.
      const bool folder = reason == "it is a directory" && std::string(command) == "check";
      CHECK_THAT(r.err, Contains(file) && Contains(folder ? "a folder without a scene file"
                                                          : "cannot read the file: " + reason));
    }
}

TEST_CASE("identify --trajectory names why the CSV cannot be read (missing file; folder; device)",
          "[cli][hostile]") {
  ScratchDir d("hostile-trajectory-reason");
  const std::string s = hostile_scene(d);
  std::vector<std::pair<std::string, std::string>> cases = unreadable_files(d, ".csv");
  cases.push_back({"/dev/zero", "not a regular file"});
  for (const auto& [file, reason] : cases) {
    const Result r = cli({"identify", s, "--trajectory", file});
    INFO(file);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("cannot read the trajectory file: " + reason));
  }
}

TEST_CASE("check's h/2 and h/4 labels never overflow or go negative for huge 1/N steps",
          "[cli][hostile]") {
  ScratchDir d("hostile-fine-label");
  // One step of 1/2^62 s, and one of 1/(2^63 - 1) s: N*2 and N*4 do not fit a long long.
  const std::vector<std::pair<std::string, std::string>> steps{
      {"1/4611686018427387904", "2.168404344971009e-19"},
      {"1/9223372036854775807", "1.0842021724855044e-19"}};
  for (const auto& [step, duration] : steps) {
    put(d.file("s.toml"), "name = \"tiny\"\nduration = " + duration + "\ntimestep = \"" + step +
                              "\"\n[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\nname = "
                              "\"c\"\nposition = [0.0, 1.0, 0.0]\n");
    const Result r = cli({"check", d.file("s.toml"), "--engine", "ours-f64"});
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Contains("own law at h = " + step + ":"));
    CHECK(r.out.find("1/-") == std::string::npos);
    CHECK(r.out.find("1/0") == std::string::npos);
    CHECK(r.out.find("h = 1/", r.out.find("h = 1/") + 1) == std::string::npos);  // h/2, h/4 in s
  }
}

TEST_CASE("Ctrl-C while gnuplot draws a report stops dropcheck and gnuplot and leaves nothing",
          "[cli][hostile]") {
  ScratchDir d("hostile-gnuplot-sigint"), bin("hostile-gnuplot-bin");
  const std::string s = hostile_scene(d);
  // A gnuplot that says it started, then hangs (as a slow plot would).
  put(bin.file("gnuplot"), "#!/bin/sh\necho $$ > '" + bin.file("started.tmp") + "'\nmv '" +
                               bin.file("started.tmp") + "' '" + bin.file("started") +
                               "'\nexec sleep 30\n");
  fs::permissions(bin.file("gnuplot"), fs::perms::owner_all);
  const pid_t pid = fork_plain();
  if (pid == 0) {
    ::signal(SIGINT, SIG_DFL);  // as in a shell (Catch2 has its own handler)
    ::setenv("PATH", (bin.path.string() + ":/usr/bin:/bin").c_str(), 1);
    std::ostringstream out, err;
    ::_exit(dropcheck::cli_main(
        {"report", s, "--engine", "ours", "--no-timing", "--out", d.file("rep")}, out, err));
  }
  const auto until = [](const std::function<bool()>& done, double seconds) {  // done() once true
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      if (done()) return true;
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  };
  int status = 0;
  bool ended = false;
  const bool started = until([&] { return fs::exists(bin.file("started")); }, 60);
  CHECK(started);
  ::kill(pid, SIGINT);
  ended = until([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, 10);
  const pid_t gnuplot = started ? std::stoi(slurp(bin.file("started"))) : -1;
  const bool gnuplot_alive = gnuplot > 0 && ::kill(gnuplot, 0) == 0;
  if (!ended) {  // the failure this test guards against: clean up, then report it
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  if (gnuplot_alive) ::kill(gnuplot, SIGKILL);
  CHECK(ended);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGINT);
  CHECK_FALSE(gnuplot_alive);
  CHECK(names(d.path) == std::set<std::string>{"tiny.toml"});
}
