// Tests the comparison report end to end (harness/report*.cpp, harness/study/evaluate.cpp and
// harness/cli/cmd_report.cpp): byte-stable output, the sections and only the metrics that apply,
// and atomic output (a bad scene file exits 2 and leaves the previous report as it was).
#include "harness/report/report.hpp"

#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "../test_dirs.hpp"
#include "harness/cli/cli.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/output_dir.hpp"
#include "harness/report/report_contact.hpp"
#include "harness/report/report_plots.hpp"
#include "harness/report/report_summary.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/harness/report/has_gnuplot.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;
namespace fs = std::filesystem;

namespace {

// Every file of a directory: name -> bytes.
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    out[e.path().filename().string()] = slurp(e.path());
  return out;
}

const char* const kThrow = R"(description = "Test scene: a cube thrown sideways with drag."
duration = 0.5
timestep = "1/60"
timesteps = ["1/30", "1/60"]

[world]
gravity = [0.0, -9.8, 0.0]
linear_damping = 1.0
contacts = false

[[body]]
name = "cube"
position = [0.0, 10.0, 0.0]
velocity = [1.0, 2.0, 0.0]
)";

int report(const std::vector<std::string>& args, std::string* err_text = nullptr) {
  std::ostringstream out, err;
  std::vector<std::string> argv{"report"};
  argv.insert(argv.end(), args.begin(), args.end());
  const int rc = cli_main(argv, out, err);
  if (err_text) *err_text = err.str();
  return rc;
}

}  // namespace

TEST_CASE("the report with --no-timing is byte-identical across two runs", "[report]") {
  ScratchDir dir("identical");
  const std::string scene = dir.write("throw.toml", kThrow);
  REQUIRE(report({scene, "--out", dir.file("a"), "--no-timing"}) == kExitOk);
  REQUIRE(report({scene, "--out", dir.file("b"), "--no-timing"}) == kExitOk);
  const auto a = contents(dir.file("a")), b = contents(dir.file("b"));
  CHECK(a.count("README.md") == 1);
  if (has_gnuplot()) {
    CHECK(a.count("throw-trajectory.svg") == 1);
    CHECK(a.count("throw-divergence.svg") == 1);
  }
  CHECK(a.count("throw-work-precision.svg") == 0);  // no timings, no work-precision plot
  CHECK(a == b);
}

TEST_CASE("the report has every section and only the metrics that apply to free flight",
          "[report]") {
  ScratchDir dir("sections");
  const std::string scene = dir.write("throw.toml", kThrow);
  std::string err;
  REQUIRE(report({scene, "--out", dir.file("out"), "--no-timing"}, &err) == kExitOk);
  CHECK_THAT(err, Contains("[1/1] throw: ours-f64 1/60 ..."));  // progress on stderr
  const std::string md = slurp(dir.path / "out" / "README.md");
  for (const char* section :
       {"## Summary", "## Provenance", "## Engines", "## How this report is made", "## Scenes",
        "### throw", "#### Divergence from ours-f64 at h = 1/60", "#### Error against each oracle",
        "closed form: max dx (m)", "own law: max dx (m)", "#### Error against run time",
        "#### Observed order of convergence", "## Determinism",
        "Test scene: a cube thrown sideways with drag."})
    CHECK_THAT(md, Contains(section));
  CHECK_THAT(
      md,
      Contains("Leaves out: no contacts: no collision shapes created; contact metrics omitted"));
  CHECK_THAT(md, !Contains("#### Landing") && !Contains("rest offset") && !Contains("⏱"));
  CHECK_THAT(md, !Contains("## Harness overhead") && !Contains("work-precision"));
  if (make_engine("bullet"))
    CHECK_THAT(md, Contains("bullet vs ours-f64:") && Contains("damping-order"));
}

TEST_CASE("a scene without a closed form has no analytic columns and uses the fine-step reference",
          "[report]") {
  ScratchDir dir("nonlinear");
  std::string text = kThrow;
  text +=
      "\n[[force]]\nspring = { anchor = [0.0, 9.0, 0.0], stiffness = 50.0, damping = 0.0, "
      "rest_length = 0.5 }\n";
  const std::string scene = dir.write("pendulum.toml", text);
  REQUIRE(report({scene, "--out", dir.file("out"), "--no-timing", "--engine", "ours-f64",
                  "--engine", "ours"}) == kExitOk);
  const std::string md = slurp(dir.path / "out" / "README.md");
  CHECK_THAT(md, !Contains("closed form: max dx"));
  CHECK_THAT(md, Contains("no closed form (spring with a rest length (nonlinear))"));
  CHECK_THAT(md, Contains("h = 1/480: max dx (m)"));  // oracle 3: finest step 1/60 divided by 8
  CHECK_THAT(md, Contains("own law: max dx (m)"));    // still free flight: oracle 2 applies
}

TEST_CASE(
    "a bad scene file exits 2 naming the file and key, and leaves the previous report untouched",
    "[report]") {
  ScratchDir dir("atomic");
  const std::string good = dir.write("throw.toml", kThrow);
  const std::string out = dir.file("out");
  REQUIRE(report({good, "--out", out, "--no-timing", "--engine", "ours-f64"}) == kExitOk);
  const auto before = contents(out);
  const std::string bad = dir.write(
      "bad.toml",
      std::string(kThrow) + "\n[[body]]\nname = \"x\"\nposition = [0.0, 1.0, 0.0]\nmass = -1.0\n");
  std::string err;
  CHECK(report({good, bad, "--out", out, "--no-timing"}, &err) == kExitBadInput);
  CHECK_THAT(err, Contains("bad.toml") && Contains("mass"));
  CHECK(contents(out) == before);
  for (const fs::directory_entry& e : fs::directory_iterator(dir.path))  // no staging left behind
    CHECK(e.path().filename().string().find("staging") == std::string::npos);
}

TEST_CASE("the report refuses to replace a directory it did not write", "[report]") {
  ScratchDir dir("refuse");
  const std::string scene = dir.write("throw.toml", kThrow);
  std::string err;
  CHECK(report({scene, "--out", dir.path.string(), "--no-timing"}, &err) == kExitBadInput);
  CHECK_THAT(err, Contains("did not write"));
  CHECK(fs::exists(dir.path / "throw.toml"));
}

TEST_CASE("with timings the run-time table has marked columns and a work-precision plot",
          "[report]") {
  ScratchDir dir("timing");
  ReportInput in;  // as little timing work as possible: this checks the plumbing only
  in.timing_options.min_run_seconds = 0.0;
  in.timing_options.warmups = 0;
  in.timing_options.samples = 2;
  std::vector<EngineSlot> engines;
  for (const char* name : {"ours", "ours-f64"})
    engines.push_back({name, [name] { return make_engine(name); }, ""});
  in.scenes.push_back(evaluate_scene(load_scene(dir.write("throw.toml", kThrow)), engines));
  time_evaluations(in.scenes, engines, in.timing_options);
  for (const EngineSlot& e : engines) in.engines.push_back(e.make()->info());
  write_report(in, dir.path.string());
  const std::string md = slurp(dir.path / "README.md");
  CHECK_THAT(md, Contains("⏱ min (ms per sim s)") && Contains("⏱ min / calibration") &&
                     Contains("⏱ median (ms per sim s)") && Contains("⏱ IQR (ms per sim s)") &&
                     Contains("⏱ harness overhead") &&
                     Contains("## Slowdown alert (⏱ wall time)") &&
                     Contains("## Harness overhead (⏱ wall time)") &&
                     Contains("## Timing reproducibility (⏱ wall time)") &&
                     Contains("#### Error against run time (⏱ wall time)") &&
                     Contains("work-precision (⏱ wall time)"));
  for (const EngineEvaluation& ev : in.scenes[0].engines)
    for (const StepEvaluation& st : ev.sweep) CHECK(st.timing);
  if (has_gnuplot()) CHECK(fs::exists(dir.path / "throw-work-precision.svg"));
}

TEST_CASE("a report written again into its folder states how far each median moved", "[report]") {
  ScratchDir dir("previous-timings");
  const std::string out = dir.file("out");
  std::vector<EngineSlot> engines{{"ours-f64", [] { return make_engine("ours-f64"); }, ""}};
  const Scene scene = load_scene(dir.write("throw.toml", kThrow));
  // One report into `out` as cmd_report writes it (staged, then swapped in), with as little timing
  // work as possible: this checks the plumbing, not the figures.
  const auto write = [&] {
    ReportInput in;
    in.timing_options.min_run_seconds = 0.0;
    in.timing_options.warmups = 0;
    in.timing_options.samples = 4;
    in.provenance.commit = "abc1234";
    in.engines.push_back(make_engine("ours-f64")->info());
    in.scenes.push_back(evaluate_scene(scene, engines));
    time_evaluations(in.scenes, engines, in.timing_options);
    in.previous = read_previous_timings(out);
    StagingDir staging(out);
    write_report(in, staging.path());
    staging.commit();
    return in.previous;
  };

  CHECK(!write().record);
  CHECK_THAT(slurp(out + "/README.md"), Contains("No earlier timings in this folder"));
  const TimingRecord first = parse_timing_record(slurp(out + "/timings.json"), "timings.json");
  REQUIRE(first.cells.size() == 2);  // ours-f64 at 1/30 and 1/60
  CHECK(first.commit == "abc1234");
  CHECK(first.cells[1].h == "1/60");
  CHECK(first.cells[1].value({}) > 0);
  CHECK(first.cells[1].full_ms.size() == 4);
  CHECK(first.cells[1].calibration_ms.size() == 4);
  CHECK_THAT(slurp(out + "/README.md"),
             Contains("## Slowdown alert") && Contains("Nothing to compare with"));

  CHECK(write().record);
  CHECK_THAT(slurp(out + "/README.md"),
             Contains("Against the report this one replaced (commit abc1234; this one: commit "
                      "abc1234), per figure") &&
                 Contains("Same commit and CPU: this is the run-to-run spread") &&
                 Contains("| minimum (headline) | ") &&
                 Contains("| minimum / calibration (side by side) | ") && Contains(" of 2 (") &&
                 Contains("| throw | ours-f64 | 1/"));

  // A damaged record is no reason to refuse the report: it says why there is no comparison, and
  // the record is written afresh.
  std::ofstream(out + "/timings.json", std::ios::trunc) << "{\"commit\": 1";
  const PreviousTimings damaged = write();
  CHECK(!damaged.record);
  CHECK_THAT(damaged.warning, Contains(out + "/timings.json") && Contains("not a timings record"));
  CHECK_THAT(slurp(out + "/README.md"), Contains("could not be read"));
  CHECK(parse_timing_record(slurp(out + "/timings.json"), "t").cells.size() == 2);
}

TEST_CASE("the timings of a previous report are read only from a regular file, never a link",
          "[report]") {
  ScratchDir dir("previous-special");
  CHECK_THAT(read_previous_timings(dir.file("absent")).note, Contains("No earlier timings"));
  fs::create_directories(dir.path / "dir" / "timings.json");
  const PreviousTimings d = read_previous_timings(dir.file("dir"));
  CHECK(!d.record);
  CHECK_THAT(d.warning, Contains("timings.json") && Contains("it is a directory"));
  fs::create_directories(dir.path / "link");
  fs::create_symlink("/dev/zero", dir.path / "link" / "timings.json");
  CHECK_THAT(read_previous_timings(dir.file("link")).warning, Contains("is a symbolic link"));
  fs::create_directories(dir.path / "secret");
  const std::string secret = dir.write("secret/data", "secret text");
  fs::create_directories(dir.path / "link2");
  fs::create_symlink(secret, dir.path / "link2" / "timings.json");
  const PreviousTimings l = read_previous_timings(dir.file("link2"));
  CHECK(!l.record);
  CHECK_THAT(l.warning, Contains("is a symbolic link") && !Contains("secret text"));
}

namespace {

// ODE under a declaration of the cone: its box-pyramid slide at 45 degrees leaves the cone's law.
class MisdeclaredOde : public Engine {
 public:
  MisdeclaredOde() : ode_(make_engine("ode")) {}
  EngineInfo info() const override {
    EngineInfo i = ode_->info();
    i.name = "ode-as-cone";
    i.friction_model = FrictionModel::cone;
    return i;
  }
  std::string cannot_run(const Scene& scene) const override { return ode_->cannot_run(scene); }
  void load(const Scene& scene, double h) override { ode_->load(scene, h); }
  void set_forces(std::span<const Vec3> forces) override { ode_->set_forces(forces); }
  void step() override { ode_->step(); }
  void read(std::span<BodyState> out) const override { ode_->read(out); }

 private:
  std::unique_ptr<Engine> ode_;
};

}  // namespace

TEST_CASE("the summary flags an engine off its slide law, once per engine", "[report][contact]") {
  if (!make_engine("ode")) return;
  const Scene scene =
      load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/slide_diagonal.toml");
  const std::vector<EngineSlot> engines{
      {"ode", [] { return make_engine("ode"); }, ""},
      {"ode-as-cone", [] { return std::make_unique<MisdeclaredOde>(); }, ""}};
  const SceneEvaluation se = evaluate_scene(scene, engines);
  CHECK(departed_laws(se, se.engines[0]).empty());
  CHECK(departed_laws(se, se.engines[1]) == std::vector<ContactLaw>{ContactLaw::slide});
  CHECK(summarize(se).verdict == "**OFF SLIDE LAW**: ode-as-cone");
}

TEST_CASE("a slide scene's trajectory plot is the distance slid, with Coulomb's closed form",
          "[report]") {
  ReportInput in;
  std::vector<EngineSlot> engines{{"ours-f64", [] { return make_engine("ours-f64"); }, ""}};
  in.scenes.push_back(
      evaluate_scene(load_scene(DROPCHECK_SOURCE_DIR "/scenarios/slide_stop.toml"), engines));
  for (const EngineSlot& e : engines) in.engines.push_back(e.make()->info());
  const std::vector<std::vector<ReportPlot>> plots = report_plots(in);
  REQUIRE(plots.size() == 1);
  const auto it = std::find_if(plots[0].begin(), plots[0].end(), [](const ReportPlot& p) {
    return p.file == "slide_stop-trajectory.svg";
  });
  REQUIRE(it != plots[0].end());
  CHECK(it->spec.ylabel == "s (m)");
  REQUIRE(it->spec.series.size() == 2);  // ours-f64 and the closed form
  // ours-f64 follows the clamp law: 2.509472 m by step 62, and no farther.
  CHECK(it->spec.series[0].y.back() == Approx(2.509472).margin(1e-6));
  // The closed form: v0^2/(2*mu*g) = 25/9.8 = 2.5510 m once stopped, at t = 4 s.
  CHECK(it->spec.series[1].title == "closed form");
  CHECK(it->spec.series[1].x.back() == Approx(4.0));
  CHECK(it->spec.series[1].y.back() == Approx(25.0 / 9.8).epsilon(1e-12));
}
