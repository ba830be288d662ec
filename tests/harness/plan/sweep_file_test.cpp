// Tests harness/plan/sweep_file.cpp and plan.cpp: a sweep file is refused with its file, line, key
// and problem before any cell runs; a plan is the same bytes from the same inputs, its hash follows
// every scene's text, and a cell's shard depends on its key alone.
#include "harness/plan/sweep_file.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>
#include <map>

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/plan/cell_record.hpp"
#include "harness/plan/plan.hpp"
#include "harness/plan/worker.hpp"
#include "harness/run/isolated_run.hpp"
#include "tests/harness/test_dirs.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

SweepSpec load_sweep_known(const std::string& path) {
  return load_sweep(path, known_engine_names());
}

const std::string kFall = std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/free_fall.toml";

std::string sweep_text(const std::string& scenes, const std::string& axes) {
  return "scenes = [" + scenes + "]\nengines = [\"ours\", \"ours-f64\"]\n" + axes;
}

std::string sweep_refusal(const ScratchDir& d, const std::string& text) {
  const std::string path = d.write("s.toml", text);
  try {
    make_plan(load_sweep(path, known_engine_names()));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a bad sweep file is refused naming the file, line, key and problem", "[plan]") {
  ScratchDir d("sweep-refusals");
  const std::string spring = "\"" + kStiffSpringScene + "\"";
  CHECK_THAT(sweep_refusal(d, sweep_text(spring, "colour = 1\n")),
             Contains("s.toml:3: colour: unknown key"));
  CHECK_THAT(sweep_refusal(d, sweep_text(spring, "[[axis]]\nname = \"wind\"\nvalues = [1]\n")),
             Contains("axis[0].name: unknown axis 'wind'"));
  CHECK_THAT(sweep_refusal(d, "scenes = [" + spring + "]\nengines = [\"havok\"]\n"),
             Contains("engines[0]: unknown engine 'havok'"));
  CHECK_THAT(
      sweep_refusal(
          d,
          sweep_text(spring, "[[axis]]\nname = \"timestep\"\nfrom = 0.01\nto = 0.1\ncount = 0\n")),
      Contains("axis[0].count: must be a whole number"));
  CHECK_THAT(
      sweep_refusal(d, sweep_text(spring,
                                  "[[axis]]\nname = \"damping_rate\"\nfrom = 0.0\nto = 1.0\ncount "
                                  "= 3\nscale = \"log\"\n")),
      Contains("a log range needs from > 0"));
  CHECK_THAT(
      sweep_refusal(d, sweep_text(spring, "[[axis]]\nname = \"scalar\"\nvalues = [\"f16\"]\n")),
      Contains("expected \"f32\" or \"f64\""));
  CHECK_THAT(
      sweep_refusal(d, sweep_text(spring,
                                  "[[axis]]\nname = \"gravity\"\nvalues = [1.0]\n[[axis]]\nname = "
                                  "\"gravity\"\nvalues = [2.0]\n")),
      Contains("axis gravity given twice"));
  CHECK_THAT(sweep_refusal(d, sweep_text("\"nowhere.toml\"", "")),
             Contains("not a scene file or folder"));
  // A value that cannot apply to a scene: named with the axis and the scene, before any cell runs.
  CHECK_THAT(
      sweep_refusal(d, sweep_text("\"" + kFall + "\"",
                                  "[[axis]]\nname = \"spring_stiffness\"\nvalues = [10.0]\n")),
      Contains("axis[0]: spring_stiffness = 10 on scene free_fall") && Contains("has no spring"));
  CHECK_THAT(sweep_refusal(
                 d, sweep_text(spring, "[[axis]]\nkey = \"body.nobody.mass\"\nvalues = [2.0]\n")),
             Contains("no body named 'nobody'"));
  CHECK_THAT(sweep_refusal(
                 d, sweep_text(spring, "[[axis]]\nkey = \"world.gravity[1]\"\nvalues = [inf]\n")),
             Contains("must be finite"));
}

TEST_CASE("a plan is the same bytes from the same inputs, and its hash follows the scenes' text",
          "[plan]") {
  ScratchDir d("plan-hash");
  std::filesystem::copy_file(kStiffSpringScene, d.file("spring.toml"));
  const std::string axes = "[[axis]]\nname = \"timestep\"\nvalues = [\"1/60\", \"1/30\"]\n";
  const std::string sweep = d.write("s.toml", sweep_text("\"spring.toml\"", axes));
  const Plan a = make_plan(load_sweep(sweep, known_engine_names())),
             b = make_plan(load_sweep(sweep, known_engine_names()));
  CHECK(plan_text(a) == plan_text(b));
  CHECK(a.cell_count() == 4);
  CHECK(a.cell(0).key == "spring|ours|timestep=1/60");  // named by its file
  CHECK(a.cell(3).key == "spring|ours-f64|timestep=1/30");
  // One byte more in the scene: another plan.
  d.write("spring.toml", slurp(kStiffSpringScene) + "\n");
  CHECK(make_plan(load_sweep(sweep, known_engine_names())).hash != a.hash);
  // Read back: the same plan; edited: refused.
  const std::string file = d.write("a.plan", plan_text(a));
  CHECK(plan_text(read_plan(file)) == plan_text(a));
  std::string edited = plan_text(a);
  edited.replace(edited.find("1/30"), 4, "1/31");
  CHECK_THROWS_WITH(read_plan(d.write("edited.plan", edited)), Contains("does not match its hash"));
  std::string exec = plan_text(a);
  exec.replace(exec.find("\"ours-f64\""), 10, "\"exec:/bin/sh\"");
  CHECK_THROWS_WITH(read_plan(d.write("exec.plan", exec)), Contains("unknown engine"));
}

TEST_CASE("a cell's shard depends on its key alone: a larger sweep moves no cell", "[plan]") {
  ScratchDir d("plan-shards");
  const std::string spring = "\"" + kStiffSpringScene + "\"";
  const Plan small = make_plan(load_sweep_known(d.write(
      "a.toml",
      sweep_text(spring, "[[axis]]\nname = \"timestep\"\nvalues = [\"1/60\", \"1/30\"]\n"))));
  const Plan large = make_plan(load_sweep_known(d.write(
      "b.toml",
      sweep_text(
          spring,
          "[[axis]]\nname = \"timestep\"\nvalues = [\"1/120\", \"1/60\", \"1/45\", \"1/30\"]\n"))));
  std::map<std::string, std::size_t> in_large;
  for (std::size_t i = 0; i < large.cell_count(); ++i)
    in_large[large.cell(i).key] = shard_of(large.cell(i).key, 7);
  for (std::size_t i = 0; i < small.cell_count(); ++i) {
    const std::string key = small.cell(i).key;
    REQUIRE(in_large.count(key));
    CHECK(shard_of(key, 7) == in_large[key]);
  }
}

TEST_CASE("a range's values end where they were asked, in the shortest text", "[plan]") {
  ScratchDir d("plan-range");
  const SweepSpec s = load_sweep_known(d.write(
      "s.toml",
      sweep_text("\"" + kStiffSpringScene + "\"",
                 "[[axis]]\nname = \"spring_stiffness\"\nfrom = 100.0\nto = 10000.0\ncount = 3\n"
                 "scale = \"log\"\n[[axis]]\nname = \"damping_rate\"\nfrom = 0.0\nto = 1.0\n"
                 "count = 3\n")));
  CHECK(s.axes[0].values == std::vector<std::string>{"100", "1000", "10000"});
  CHECK(s.axes[1].values == std::vector<std::string>{"0", "0.5", "1"});
}

TEST_CASE("a plan read back is checked whatever its hash says", "[plan]") {
  ScratchDir d("plan-crafted");
  const Plan good = make_plan(load_sweep_known(
      d.write("s.toml", sweep_text("\"" + kStiffSpringScene + "\"",
                                   "[[axis]]\nname = \"damping_rate\"\nvalues = [0.5, 1.0]\n"))));
  // Each change below comes with its hash recomputed, as anyone can.
  auto crafted = [&](const std::function<void(Plan&)>& change) {
    Plan p = good;
    change(p);
    p.hash = plan_hash(p);
    try {
      read_plan(d.write("crafted.plan", plan_text(p)));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(crafted([](Plan&) {}).empty());  // the plan itself reads back
  CHECK_THAT(crafted([](Plan& p) { p.axes[0].values[0] = " 0.5"; }), Contains("not a finite"));
  CHECK_THAT(crafted([](Plan& p) { p.axes[0].values[0] = "0.50"; }), Contains("shortest"));
  CHECK_THAT(crafted([](Plan& p) { p.axes[0].values[1] = "0.5"; }), Contains("twice"));
  CHECK_THAT(crafted([](Plan& p) { p.scenes.push_back(p.scenes[0]); }), Contains("two scenes"));
  CHECK_THAT(crafted([](Plan& p) { p.scenes[0].text = "duration = -1\n"; }),
             Contains("not a valid plan"));
  CHECK_THAT(crafted([](Plan& p) {
               p.axes[0].kind = AxisKind::scene_key;
               p.axes[0].name = "world.gravity[0]\x1b[2J";
             }),
             Contains("axis name") && !Contains("\x1b"));
  CHECK_THAT(crafted([](Plan& p) { p.engines.push_back("exec:/bin/sh"); }),
             Contains("unknown engine"));
  CHECK_THAT(crafted([](Plan& p) {
               p.axes.assign(64, p.axes[0]);
               for (std::size_t i = 0; i < p.axes.size(); ++i) {
                 p.axes[i].kind = AxisKind::scene_key;
                 p.axes[i].name = "a" + std::to_string(i);
               }
             }),
             Contains("cells"));
}

TEST_CASE("the same sweep planned from another folder is the same plan", "[plan]") {
  ScratchDir d("plan-paths");
  for (const char* sub : {"a", "b/c"}) {
    std::filesystem::create_directories(d.path / sub);
    std::filesystem::copy_file(kStiffSpringScene, d.path / sub / "stiff_spring.toml");
  }
  const std::string axes = "[[axis]]\nname = \"timestep\"\nvalues = [\"1/60\"]\n";
  const Plan a =
      make_plan(load_sweep_known(d.write("a/s.toml", sweep_text("\"stiff_spring.toml\"", axes))));
  const Plan b =
      make_plan(load_sweep_known(d.write("b/c/s.toml", sweep_text("\"stiff_spring.toml\"", axes))));
  CHECK(a.scenes[0].file != b.scenes[0].file);
  CHECK(a.hash == b.hash);
}

TEST_CASE("a scene folder's link is refused, and a sweep past 2e6 cells stops at its axis",
          "[plan]") {
  ScratchDir d("plan-limits");
  std::filesystem::create_directories(d.path / "scenes");
  std::filesystem::copy_file(kStiffSpringScene, d.path / "scenes" / "a.toml");
  std::filesystem::create_symlink(kFall, d.path / "scenes" / "b.toml");
  CHECK_THAT(sweep_refusal(d, sweep_text("\"scenes\"", "")), Contains("not a regular file"));
  std::filesystem::remove(d.path / "scenes" / "b.toml");
  std::string axes;
  for (const char* key : {"world.gravity[0]", "world.gravity[1]", "world.gravity[2]", "duration"})
    axes += std::string("[[axis]]\nkey = \"") + key + "\"\nfrom = 1.0\nto = 2.0\ncount = 100\n";
  // 1 scene x 2 engines x 100^3 = 2e6 cells is allowed; the fourth axis takes it to 2e8.
  CHECK_THAT(sweep_refusal(d, sweep_text("\"scenes\"", axes)),
             Contains("axis[3]") && Contains("more than the 2e+06"));
}

TEST_CASE("a shard's worker writes the records the per-cell path writes, byte for byte",
          "[plan][worker]") {
  const Plan plan = make_plan(
      load_sweep(std::string(DROPCHECK_SOURCE_DIR) + "/sweeps/small.toml", known_engine_names()));
  std::vector<std::size_t> cells;
  for (std::size_t i = 0; i < plan.cell_count(); i += 3) cells.push_back(i);  // 86 of 256
  const std::vector<CellRecord> worker = run_cells_in_worker(plan, cells);
  for (std::size_t k = 0; k < cells.size(); ++k) {  // each run forked, as `dropcheck sweep` did
    const CellRecord alone = run_cell(plan, plan.cell(cells[k]), Isolation::child_process);
    INFO(plan.cell(cells[k]).key);
    CHECK(worker[k].status == alone.status);
    CHECK(worker[k].line == alone.line);
  }
}

TEST_CASE(
    "an engine that aborts in a shard's worker is that cell's record, as the per-cell path "
    "writes it, and the next cells run",
    "[plan][worker]") {
  ScratchDir d("plan-worker-crash");
  // Chipmunk (built with its debug checks) aborts on an infinite velocity: measured SIGABRT at
  // step 65 with a 1e12 N/m spring at 1/20 s (cpBody.c:107).
  const Plan plan = make_plan(load_sweep_known(d.write(
      "s.toml", "scenes = [\"" + kStiffSpringScene +
                    "\"]\nengines = [\"chipmunk\", \"ours-f64\"]\n[[axis]]\n"
                    "key = \"force[0].spring.stiffness\"\nvalues = [3600.0, 1e12]\n[[axis]]\n"
                    "name = \"timestep\"\nvalues = [\"1/20\"]\n")));
  std::vector<std::size_t> cells(plan.cell_count());
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = i;
  const std::vector<CellRecord> worker = run_cells_in_worker(plan, cells);
  REQUIRE(worker.size() == 4);
  CHECK(worker[1].status == "crashed");  // chipmunk at 1e12, the second cell: the worker died
  CHECK_THAT(worker[1].line, Contains("SIGABRT"));
  CHECK(worker[2].status == "ok");          // ours-f64 ran after it, in a new worker
  CHECK(worker[3].status == "non-finite");  // (1e12 N/m: Inf by step 33)
  for (std::size_t k = 0; k < cells.size(); ++k)
    CHECK(worker[k].line == run_cell(plan, plan.cell(cells[k]), Isolation::child_process).line);
  // Two workers side by side: the one that dies is replaced while cells are left, and every
  // record is the same.
  WorkerStats two;
  const std::vector<CellRecord> side =
      run_cells_in_worker(plan, cells, {}, kWorkerSilenceLimit, &two, 2);
  CHECK(two.rerun_alone == 1);
  CHECK(two.workers >= 2);
  for (std::size_t k = 0; k < cells.size(); ++k) CHECK(side[k].line == worker[k].line);
}

TEST_CASE(
    "a worker silent past its limit is killed, its cell is run alone with the per-cell path's "
    "bytes, and a new worker takes the next cell",
    "[plan][worker]") {
  ScratchDir d("plan-worker-silent");
  // Simbody's error-controlled integrator at h = 5e-5 s: 2e4 steps, 3.5 times the watchdog's 0.2 s
  // in a release build (5e4 steps took 1.74-1.78 s, three runs of `dropcheck run`), and longer
  // under the sanitizers; at 1/60 a cell takes milliseconds.
  const Plan plan = make_plan(load_sweep_known(
      d.write("s.toml", "scenes = [\"" + kFall +
                            "\"]\nengines = [\"simbody-rkm\"]\n[[axis]]\n"
                            "name = \"timestep\"\nvalues = [\"1/60\", \"1/20000\", \"1/30\"]\n")));
  REQUIRE(plan.cell_count() == 3);
  const std::vector<std::size_t> cells{0, 1, 2};
  WorkerStats stats;
  const std::vector<CellRecord> worker =
      run_cells_in_worker(plan, cells, {}, std::chrono::milliseconds(200), &stats);
  CHECK(stats.workers == 2);      // the second worker started after the silent one was killed
  CHECK(stats.rerun_alone == 1);  // the 2e4-step cell
  for (std::size_t k = 0; k < cells.size(); ++k) {
    INFO(plan.cell(cells[k]).key);
    CHECK(worker[k].status == "ok");
    CHECK(worker[k].line == run_cell(plan, plan.cell(cells[k]), Isolation::child_process).line);
  }
}

TEST_CASE("the worker writes the per-cell bytes for the engines small.toml leaves out",
          "[plan][worker]") {
  ScratchDir d("plan-worker-slow-engines");
  // Simbody (both integrators) and DART take microseconds a body-step, too slow for small.toml's
  // 256 cells; two steps on the drag scene and the spring show their records are the same too.
  const Plan plan = make_plan(load_sweep_known(
      d.write("s.toml", "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
                            "/scenarios/free_fall_drag.toml\", \"" + kStiffSpringScene +
                            "\"]\nengines = [\"simbody\", \"simbody-rkm\", \"dart\"]\n[[axis]]\n"
                            "name = \"timestep\"\nvalues = [\"1/60\", \"1/30\"]\n")));
  std::vector<std::size_t> cells(plan.cell_count());
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = i;
  const std::vector<CellRecord> worker = run_cells_in_worker(plan, cells);
  std::map<std::string, int> statuses;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    INFO(plan.cell(cells[k]).key);
    ++statuses[worker[k].status];
    CHECK(worker[k].line == run_cell(plan, plan.cell(cells[k]), Isolation::child_process).line);
  }
  CHECK(statuses["ok"] >= 8);  // every cell but simbody-rkm's spring (refused: "skipped")
}

TEST_CASE("the shipped sweeps plan: small.toml a few hundred cells, large.toml over 1e5",
          "[plan]") {
  const std::string dir = std::string(DROPCHECK_SOURCE_DIR) + "/sweeps/";
  CHECK(make_plan(load_sweep_known(dir + "small.toml")).cell_count() == 256);
  const Plan large = make_plan(load_sweep_known(dir + "large.toml"));
  CHECK(large.cell_count() == 440000);  // the figure its description states
  CHECK(large.axes.size() == 4);
}

TEST_CASE(
    "a timed-out cell's record names its limit, not the step it reached: the same bytes twice",
    "[plan][worker]") {
  ScratchDir d("plan-timed-out");
  // 5e4 steps of Simbody's error-controlled integrator (1.7 s or more) against a 0.1 s limit: the
  // step reached differs from run to run, the record does not.
  const Plan plan = make_plan(
      load_sweep_known(d.write("s.toml", "scenes = [\"" + kFall +
                                             "\"]\nengines = [\"simbody-rkm\"]\n[[axis]]\n"
                                             "name = \"timestep\"\nvalues = [\"1/50000\"]\n")));
  const CellRecord first = run_cell(plan, plan.cell(0), Isolation::child_process, 0.1);
  const CellRecord second = run_cell(plan, plan.cell(0), Isolation::child_process, 0.1);
  CHECK(first.status == "timed-out");
  CHECK_THAT(first.line, Contains("\"reason\":\"no result within the limit of 0.1 s\""));
  CHECK_THAT(first.line, !Contains("failed_step") && !Contains("killed"));
  CHECK(first.line == second.line);
  // In this process with the same limit (a shard's worker): checked after every step, the same
  // record.
  const CellRecord here = run_cell(plan, plan.cell(0), Isolation::in_process, 0.1);
  CHECK(here.line == first.line);
}

TEST_CASE("a plan that is not JSON is refused with an escaped, short excerpt of where it stopped",
          "[plan][hostile]") {
  // The JSON parser quotes the bytes it stopped at as they are: a C1 control (CSI) or a long token
  // reached the terminal whole (fuzz/regressions/plan_reader/parse_error_c1_byte.plan).
  auto error_of = [](const std::string& text) {
    try {
      parse_plan(text, "p.plan");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  const std::string c1 = error_of("{\"a\":\x9b[31m}");
  CHECK_THAT(c1, Contains("p.plan: not a dropcheck plan: '[json.exception.parse_error.101]") &&
                     Contains("\\x9b"));
  CHECK(find_unsafe_byte(c1) == std::string::npos);
  CHECK(error_of("{\"a\":\"" + std::string(100000, 'a') + "\x01\"}").size() < 1024);
  CHECK_THAT(error_of(R"({"format":"dropcheck-plan/1","sweep":"","description":"","engines":[],)"
                      R"("measure":[],"axes":[{"key":"a\u001b[2J","values":[]}]})"),
             Contains("axis 'a\\x1b[2J' has no values"));
}
