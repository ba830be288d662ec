// Tests `dropcheck plan`, `sweep` and `merge` as a user runs them: the merged result is the same
// bytes for any number of shards; a missing shard is listed and rerun from the list; a cell
// recorded twice with different bytes, a record of another plan and a planted link are refused,
// naming the files; an engine that blows up is a record, not a failed shard.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/cli/cli.hpp"
#include "tests/harness/test_dirs.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

struct Cli {
  int code = 0;
  std::string out, err;
};

Cli run_sweep_cli(const std::vector<std::string>& argv) {
  std::ostringstream out, err;
  const int code = cli_main(argv, out, err);
  return {code, out.str(), err.str()};
}

// 2 engines x 4 steps x 2 stiffnesses of the stiff spring: 16 cells. At 1/25 and 3600 N/m ours
// (float) passes its stability edge and overflows (non-finite at step 68).
std::string make_plan_file(const ScratchDir& d) {
  const std::string sweep = d.write(
      "s.toml",
      "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
          "/scenarios/extreme/stiff_spring.toml\"]\n"
          "engines = [\"ours\", \"chipmunk\"]\n"
          "[[axis]]\nname = \"timestep\"\nvalues = [\"1/120\", \"1/60\", \"1/32\", \"1/25\"]\n"
          "[[axis]]\nkey = \"force[0].spring.stiffness\"\nvalues = [900.0, 3600.0]\n");
  const Cli p = run_sweep_cli({"plan", sweep, "--out", d.file("p.plan")});
  REQUIRE(p.code == 0);
  CHECK_THAT(p.out, Contains("16 cells"));
  return d.file("p.plan");
}

void run_shards(const std::string& plan, const std::string& dir, int n) {
  for (int i = 1; i <= n; ++i)
    REQUIRE(run_sweep_cli({"sweep", plan, "--shard", std::to_string(i) + "/" + std::to_string(n),
                           "--out", dir, "--quiet"})
                .code == 0);
}

}  // namespace

TEST_CASE("sweep: the merged result is the same bytes for 1, 7, 20 and 1000 shards",
          "[plan][cli]") {
  ScratchDir d("sweep-shards");
  const std::string plan = make_plan_file(d);
  std::vector<std::string> results;
  for (int n : {1, 7, 20, 1000}) {
    const std::string dir = d.file("shards-" + std::to_string(n));
    run_shards(plan, dir, n);
    const std::string out = d.file("r" + std::to_string(n) + ".jsonl");
    const Cli m = run_sweep_cli({"merge", plan, dir, "--out", out});
    REQUIRE(m.code == 0);
    CHECK_THAT(m.out, Contains("16 records"));
    results.push_back(slurp(out));
  }
  CHECK(results[0] == results[1]);
  CHECK(results[0] == results[2]);
  CHECK(results[0] == results[3]);
  // Each record names its cell, plan and build; the blown-up cells are records.
  CHECK_THAT(
      results[0],
      Contains("\"key\":\"stiff_spring|chipmunk|timestep=1/120|force[0].spring.stiffness=900\""));
  CHECK_THAT(results[0], Contains("\"build\":{\"key\":"));
  CHECK_THAT(results[0], Contains("\"status\":\"non-finite\""));
  // Rerunning a shard replaces its file with the same bytes.
  const std::string first = slurp(d.file("shards-7/shard-3-of-7.jsonl"));
  REQUIRE(run_sweep_cli({"sweep", plan, "--shard", "3/7", "--out", d.file("shards-7"), "--quiet"})
              .code == 0);
  CHECK(slurp(d.file("shards-7/shard-3-of-7.jsonl")) == first);
  // Side by side on 1, 2 and 5 workers: the same bytes (the records are sorted by key).
  for (const char* jobs : {"1", "2", "5"}) {
    const std::string dir = d.file(std::string("jobs-") + jobs);
    REQUIRE(
        run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", dir, "--jobs", jobs, "--quiet"})
            .code == 0);
    CHECK(slurp(dir + "/shard-1-of-1.jsonl") == slurp(d.file("shards-1/shard-1-of-1.jsonl")));
  }
}

TEST_CASE("merge lists missing cells, and sweep --cells-from runs just those", "[plan][cli]") {
  ScratchDir d("sweep-missing");
  const std::string plan = make_plan_file(d), dir = d.file("shards");
  run_shards(plan, dir, 4);
  run_shards(plan, d.file("whole"), 1);
  REQUIRE(run_sweep_cli({"merge", plan, d.file("whole"), "--out", d.file("whole.jsonl")}).code ==
          0);
  std::filesystem::remove(dir + "/shard-2-of-4.jsonl");
  const Cli m = run_sweep_cli({"merge", plan, dir, "--out", d.file("r.jsonl")});
  CHECK(m.code == 1);
  CHECK_THAT(m.err, Contains("cells missing"));
  CHECK_FALSE(std::filesystem::exists(d.file("r.jsonl")));
  const Cli again =
      run_sweep_cli({"sweep", plan, "--cells-from", d.file("r.jsonl.missing"), "--out", dir});
  REQUIRE(again.code == 0);
  REQUIRE(run_sweep_cli({"merge", plan, dir, "--out", d.file("r.jsonl")}).code == 0);
  CHECK(slurp(d.file("r.jsonl")) == slurp(d.file("whole.jsonl")));
}

TEST_CASE(
    "merge refuses a cell recorded twice with different bytes, another plan's record and a "
    "planted link, naming the files",
    "[plan][cli]") {
  ScratchDir d("sweep-refusals");
  const std::string plan = make_plan_file(d), dir = d.file("shards");
  run_shards(plan, dir, 1);
  const std::string whole = slurp(dir + "/shard-1-of-1.jsonl");
  // The same bytes twice (a shard rerun beside the first run) are one record.
  d.write("shards/cells-copy.jsonl", whole.substr(0, whole.find('\n') + 1));
  CHECK(run_sweep_cli({"merge", plan, dir, "--out", d.file("r.jsonl")}).code == 0);
  // Different bytes for one cell: both files named.
  std::string changed = whole.substr(0, whole.find('\n') + 1);
  changed.replace(changed.find("\"hash\":\"") + 8, 4, "0000");
  d.write("shards/cells-copy.jsonl", changed);
  Cli m = run_sweep_cli({"merge", plan, dir, "--out", d.file("r2.jsonl")});
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Contains("cells-copy.jsonl") && Contains("shard-1-of-1.jsonl:1") &&
                        Contains("different bytes"));
  // Another plan's record.
  std::string other = whole.substr(0, whole.find('\n') + 1);
  other.replace(other.find("\"plan\":\"") + 8, 16, "0123456789abcdef");
  d.write("shards/cells-copy.jsonl", other);
  m = run_sweep_cli({"merge", plan, dir, "--out", d.file("r2.jsonl")});
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Contains("belongs to plan"));
  // A planted link among the shard files: refused, not followed.
  std::filesystem::remove(dir + "/cells-copy.jsonl");
  std::filesystem::create_symlink("/etc/passwd", dir + "/shard-9-of-9.jsonl");
  m = run_sweep_cli({"merge", plan, dir, "--out", d.file("r2.jsonl")});
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Contains("not a regular file"));
  CHECK_THAT(m.err, !Contains("root:"));
  // A link planted where a shard is written: refused, and what it points at is untouched.
  std::filesystem::remove(dir + "/shard-9-of-9.jsonl");
  const std::string victim = d.write("victim.txt", "keep me\n");
  std::filesystem::create_symlink(victim, dir + "/shard-1-of-2.jsonl");
  CHECK(run_sweep_cli({"sweep", plan, "--shard", "1/2", "--out", dir, "--quiet"}).code == 2);
  CHECK(slurp(victim) == "keep me\n");
}

TEST_CASE("sweep and plan refuse bad arguments with exit 2", "[plan][cli]") {
  ScratchDir d("sweep-args");
  const std::string plan = make_plan_file(d);
  CHECK_THAT(run_sweep_cli({"sweep", plan, "--shard", "0/7", "--out", d.file("x")}).err,
             Contains("--shard: expected 1 <= I <= N"));
  CHECK(run_sweep_cli({"sweep", plan, "--shard", "8/7", "--out", d.file("x")}).code == 2);
  for (const char* jobs : {"0", "-1", "2x", "99999"})
    CHECK_THAT(
        run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("x"), "--jobs", jobs}).err,
        Contains("--jobs: expected a whole number of workers from 1 to 1024"));
  CHECK(run_sweep_cli({"sweep", plan, "--out", d.file("x")}).code ==
        2);  // neither --shard nor --cells-from
  CHECK(run_sweep_cli({"sweep", d.write("junk.plan", "{}"), "--shard", "1/1", "--out", d.file("x")})
            .code == 2);
  CHECK_THAT(run_sweep_cli({"sweep", plan, "--cells-from", d.write("list", "no|such|cell\n"),
                            "--out", d.file("x")})
                 .err,
             Contains("list:1") && Contains("is not in plan"));
}

TEST_CASE(
    "sweep --cache: a cell this build already ran, in any plan, is not run again, and the "
    "result is the same bytes",
    "[plan][cli]") {
  ScratchDir d("sweep-cache");
  const std::string plan = make_plan_file(d), cache = d.file("cache");
  Cli first =
      run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("a"), "--cache", cache});
  REQUIRE(first.code == 0);
  CHECK_THAT(first.out, Contains("0 from the cache"));
  // A larger sweep: one more step. Its 16 old cells come from the cache, its 4 new ones run.
  const std::string sweep = d.write(
      "t.toml", "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
                    "/scenarios/extreme/stiff_spring.toml\"]\n"
                    "engines = [\"ours\", \"chipmunk\"]\n"
                    "[[axis]]\nname = \"timestep\"\n"
                    "values = [\"1/120\", \"1/60\", \"1/32\", \"1/25\", \"1/240\"]\n"
                    "[[axis]]\nkey = \"force[0].spring.stiffness\"\nvalues = [900.0, 3600.0]\n");
  REQUIRE(run_sweep_cli({"plan", sweep, "--out", d.file("t.plan")}).code == 0);
  Cli second = run_sweep_cli(
      {"sweep", d.file("t.plan"), "--shard", "1/1", "--out", d.file("b"), "--cache", cache});
  REQUIRE(second.code == 0);
  CHECK_THAT(second.out, Contains("20 cells") && Contains("16 from the cache"));
  REQUIRE(
      run_sweep_cli({"sweep", d.file("t.plan"), "--shard", "1/1", "--out", d.file("c"), "--quiet"})
          .code == 0);
  CHECK(slurp(d.file("b/shard-1-of-1.jsonl")) == slurp(d.file("c/shard-1-of-1.jsonl")));
  // A damaged entry is no entry: that cell runs again.
  for (const auto& e : std::filesystem::recursive_directory_iterator(cache))
    if (e.is_regular_file()) {
      std::ofstream(e.path()) << "{\"format\":\"junk\"}\n";
      break;
    }
  Cli third = run_sweep_cli(
      {"sweep", d.file("t.plan"), "--shard", "1/1", "--out", d.file("e"), "--cache", cache});
  CHECK_THAT(third.out, Contains("19 from the cache"));
  CHECK(slurp(d.file("e/shard-1-of-1.jsonl")) == slurp(d.file("c/shard-1-of-1.jsonl")));
}

TEST_CASE("sweep refuses a bad --out before running any cell", "[plan][cli]") {
  ScratchDir d("sweep-out");
  const std::string plan = make_plan_file(d);
  const std::string file = d.write("a-file", "x\n");
  const Cli c = run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", file});
  CHECK(c.code == 2);
  CHECK_THAT(c.err, Contains("is not a folder"));
  CHECK_THAT(c.err, !Contains("cell 1 of"));
  std::filesystem::create_directories(d.path / "out");
  std::filesystem::create_symlink(file, d.path / "out" / "shard-1-of-1.jsonl");
  const Cli l = run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("out")});
  CHECK(l.code == 2);
  CHECK_THAT(l.err, !Contains("cell 1 of"));
  CHECK(slurp(file) == "x\n");
}

TEST_CASE("report --results draws a sweep's maps and lists its failed cells, the same bytes twice",
          "[plan][cli][report]") {
  ScratchDir d("sweep-report");
  const std::string plan = make_plan_file(d);
  run_shards(plan, d.file("shards"), 1);
  REQUIRE(run_sweep_cli({"merge", plan, d.file("shards"), "--out", d.file("r.jsonl")}).code == 0);
  const Cli a = run_sweep_cli({"report", "--results", d.file("r.jsonl"), "--out", d.file("maps")});
  REQUIRE(a.code == 0);
  const std::string readme = slurp(d.file("maps/README.md"));
  CHECK_THAT(readme, Contains("# dropcheck sweep report"));
  // ours (float) overflows at 1/25 and 3600 N/m: a failed cell with its cause and the theory's.
  CHECK_THAT(readme, Contains("non-finite") && Contains("is unstable at h = 1/25"));
  CHECK_THAT(readme, Contains("## stiff_spring / ours"));
  CHECK(std::filesystem::exists(d.file("maps/stiff_spring-ours-stability.svg")));
  CHECK(std::filesystem::exists(d.file("maps/stiff_spring-chipmunk-error.svg")));
  const std::string svg = slurp(d.file("maps/stiff_spring-ours-stability.svg"));
  REQUIRE(run_sweep_cli({"report", "--results", d.file("r.jsonl"), "--out", d.file("maps")}).code ==
          0);
  CHECK(slurp(d.file("maps/README.md")) == readme);
  CHECK(slurp(d.file("maps/stiff_spring-ours-stability.svg")) == svg);
  // Not a result file: exit 2 before anything is written.
  const Cli bad = run_sweep_cli(
      {"report", "--results", d.write("bad.jsonl", "{\"x\":1}\n"), "--out", d.file("m2")});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Contains("bad.jsonl:1"));
  CHECK_FALSE(std::filesystem::exists(d.file("m2")));
}

TEST_CASE(
    "plan, sweep, merge and report --results never write over one of their inputs, nor through a "
    "link at any depth of a cache",
    "[plan][cli][hostile]") {
  ScratchDir d("sweep-inputs");
  const std::string plan = make_plan_file(d), dir = d.file("shards");
  const std::string plan_bytes = slurp(plan);
  const auto refused = [](const Cli& c, const std::string& key) {
    CHECK(c.code == 2);
    CHECK_THAT(c.err, Contains(key) && Contains("input"));
    CHECK_THAT(c.err, !Contains("cell 1 of"));
  };
  // plan: onto its sweep file, onto a scene the sweep names.
  const std::string sweep =
      d.write("s2.toml", "scenes = [\"" +
                             d.write("scene.toml", slurp(std::string(DROPCHECK_SOURCE_DIR) +
                                                         "/scenarios/free_fall.toml")) +
                             "\"]\nengines = [\"ours\"]\n[[axis]]\nname = \"timestep\"\nvalues = "
                             "[\"1/60\"]\n");
  const std::string sweep_bytes = slurp(sweep), scene_bytes = slurp(d.file("scene.toml"));
  refused(run_sweep_cli({"plan", sweep, "--out", sweep}), "--out");
  refused(run_sweep_cli({"plan", sweep, "--out", d.file("scene.toml")}), "--out");
  CHECK(slurp(sweep) == sweep_bytes);
  CHECK(slurp(d.file("scene.toml")) == scene_bytes);
  // sweep: its shard file onto the plan (--out being the plan's folder, the plan named so), onto
  // the --cells-from list.
  std::filesystem::create_directories(d.file("here"));
  const std::string named_like_shard = d.file("here/shard-1-of-1.jsonl");
  std::filesystem::copy_file(plan, named_like_shard);
  refused(run_sweep_cli({"sweep", named_like_shard, "--shard", "1/1", "--out", d.file("here")}),
          "--out");
  CHECK(slurp(named_like_shard) == plan_bytes);
  // merge: --out onto the plan, --out or --missing inside the shard folder, onto each other.
  run_shards(plan, dir, 1);
  refused(run_sweep_cli({"merge", plan, dir, "--out", plan}), "--out");
  CHECK(slurp(plan) == plan_bytes);
  refused(run_sweep_cli({"merge", plan, dir, "--out", dir + "/shard-1-of-1.jsonl"}), "--out");
  refused(run_sweep_cli({"merge", plan, dir, "--out", d.file("r.jsonl"), "--missing", plan}),
          "--missing");
  const Cli same = run_sweep_cli(
      {"merge", plan, dir, "--out", d.file("r.jsonl"), "--missing", d.file("r.jsonl")});
  CHECK(same.code == 2);
  CHECK_THAT(same.err, Contains("name two different files"));
  // report --results: a report folder that holds the result file.
  REQUIRE(run_sweep_cli({"merge", plan, dir, "--out", d.file("maps/r.jsonl")}).code == 0);
  const Cli rep =
      run_sweep_cli({"report", "--results", d.file("maps/r.jsonl"), "--out", d.file("maps")});
  CHECK(rep.code == 2);
  CHECK_THAT(rep.err, Contains("--out") && Contains("refusing"));
  CHECK(std::filesystem::exists(d.file("maps/r.jsonl")));
  // sweep --cache: a subfolder that is a link to a folder outside the cache is refused before any
  // cell runs, and nothing is written through it.
  const std::string cache = d.file("cache");
  REQUIRE(run_sweep_cli(
              {"sweep", plan, "--shard", "1/1", "--out", d.file("a"), "--cache", cache, "--quiet"})
              .code == 0);
  std::filesystem::path sub;
  for (const auto& e : std::filesystem::directory_iterator(cache)) sub = e.path();
  REQUIRE_FALSE(sub.empty());
  std::filesystem::create_directories(d.file("elsewhere"));
  std::filesystem::remove_all(sub);
  std::filesystem::create_symlink(d.file("elsewhere"), sub);
  const Cli linked =
      run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("b"), "--cache", cache});
  CHECK(linked.code == 2);
  CHECK_THAT(linked.err, Contains("--cache") && Contains("symbolic link"));
  CHECK_THAT(linked.err, !Contains("cell 1 of"));
  CHECK(std::filesystem::is_empty(d.file("elsewhere")));
}

TEST_CASE("a plan or a record nesting arrays past 64 levels is refused by file, not a crash",
          "[plan][cli][hostile]") {
  ScratchDir d("sweep-deep");
  const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
  const Cli s = run_sweep_cli({"sweep", d.write("deep.plan", "{\"description\":" + deep + "}"),
                               "--shard", "1/1", "--out", d.file("x")});
  CHECK(s.code == 2);
  CHECK_THAT(s.err, Contains("deep.plan") && Contains("nest deeper than 64 levels"));
  const std::string plan = make_plan_file(d);
  std::filesystem::create_directories(d.file("shards"));
  // 200,000 levels: a line under the 1 MiB a record line may take.
  const std::string record_deep = std::string(200000, '[') + std::string(200000, ']');
  d.write("shards/shard-1-of-1.jsonl",
          "{\"format\":\"dropcheck-record/1\",\"key\":\"k\",\"plan\":" + record_deep + "}\n");
  const Cli m = run_sweep_cli({"merge", plan, d.file("shards"), "--out", d.file("r.jsonl")});
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Contains("shard-1-of-1.jsonl:1") && Contains("not a JSON record"));
}

TEST_CASE("report --results escapes record text everywhere and gives two scenes two map files",
          "[plan][cli][report][hostile]") {
  ScratchDir d("sweep-escapes");
  // Hand-made records: scenes "a b" and "a_b" (one file slug), an engine name with a terminal
  // escape, a status and reason with a line break.
  std::string text;
  for (const std::string scene : {"a b", "a_b"})
    for (const std::string h : {"1/60", "1/30"})
      text += "{\"format\":\"dropcheck-record/1\",\"key\":\"" + scene +
              "|e\\u001b[31m|timestep=" + h + "\",\"scene\":\"" + scene +
              "\",\"engine\":{\"name\":\"e\\u001b[31m\"},\"axes\":{\"timestep\":\"" + h +
              "\"},\"status\":\"odd\\nstatus\",\"reason\":\"line\\n## injected\","
              "\"stability\":{\"theory_max_h\":null,\"law_unstable\":\"\"}}\n";
  const std::string results = d.write("r.jsonl", text);
  const Cli c = run_sweep_cli({"report", "--results", results, "--out", d.file("maps")});
  REQUIRE(c.code == 0);
  CHECK_THAT(c.err, !Contains("\x1b"));
  const std::string readme = slurp(d.file("maps/README.md"));
  CHECK_THAT(readme, !Contains("\x1b") && !Contains("\n## injected"));
  CHECK_THAT(readme, Contains("\\x1b[31m"));
  std::size_t svgs = 0;
  for (const auto& e : std::filesystem::directory_iterator(d.file("maps")))
    svgs += e.path().extension() == ".svg";
  CHECK(svgs == 2);  // one stability map per scene, none written over the other
}

TEST_CASE("plan refuses what run refuses, and one step written two ways", "[plan][cli][hostile]") {
  ScratchDir d("sweep-limits");
  const auto sweep = [&](const std::string& values) {
    return d.write("s.toml", "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
                                 "/scenarios/free_fall.toml\"]\nengines = [\"ours\"]\n"
                                 "[[axis]]\nname = \"timestep\"\nvalues = [" +
                                 values + "]\n");
  };
  // 1e-9 s: 10^9 steps, as `run --dt 1e-9` refuses them.
  const Cli tiny = run_sweep_cli({"plan", sweep("\"1e-9\""), "--out", d.file("p.plan")});
  CHECK(tiny.code == 2);
  CHECK_THAT(tiny.err, Contains("s.toml") && Contains("exceed the limit of 20000000 steps"));
  CHECK_FALSE(std::filesystem::exists(d.file("p.plan")));
  // "1/60" and "1/060" are one step: one text, so listed twice.
  const Cli twice =
      run_sweep_cli({"plan", sweep("\"1/60\", \"1/060\""), "--out", d.file("p.plan")});
  CHECK(twice.code == 2);
  CHECK_THAT(twice.err, Contains("1/60 appears twice"));
  const Cli seconds =
      run_sweep_cli({"plan", sweep("\"0.0010\", 0.001"), "--out", d.file("p.plan")});
  CHECK(seconds.code == 2);
  CHECK_THAT(seconds.err, Contains("0.001 appears twice (as 0.0010)"));
}

namespace {

// An engine file in `d` running tests/adapters/bad_engine.py MODE at step STEP, named `name`.
std::string bad_engine_file(const ScratchDir& d, const std::string& file, const std::string& name,
                            const std::string& mode) {
  return d.write(file, "name = \"" + name + "\"\ncommand = [\"python3\", \"" +
                           std::string(DROPCHECK_SOURCE_DIR) +
                           "/tests/adapters/bad_engine.py\", \"" + mode +
                           "\", \"3\"]\ntimeout = 2.0\n");
}

}  // namespace

TEST_CASE(
    "a sweep names engine files: the plan fingerprints them, sweep runs them only when given, a "
    "changed one is refused, and one that hangs or dies costs its cells only",
    "[plan][cli][exec]") {
  ScratchDir d("sweep-external");
  const std::string good = bad_engine_file(d, "good.toml", "steady", "none");
  const std::string hang = bad_engine_file(d, "hang.toml", "stuck", "hang");
  const std::string crash = bad_engine_file(d, "crash.toml", "falls", "crash");
  const std::string sweep = d.write(
      "s.toml", "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
                    "/scenarios/free_fall_drag.toml\"]\n"
                    "engines = [\"ours-f64\", \"good.toml\", \"hang.toml\", \"crash.toml\"]\n"
                    "[[axis]]\nname = \"timestep\"\nvalues = [\"1/120\", \"1/60\"]\n");
  const Cli p = run_sweep_cli({"plan", sweep, "--out", d.file("p.plan"), "--keys"});
  REQUIRE(p.code == 0);
  // Each external engine's cells carry its name and fingerprint.
  CHECK_THAT(p.out, Contains("8 cells") && Contains("free_fall_drag|steady@") &&
                        Contains("free_fall_drag|stuck@") && Contains("free_fall_drag|falls@"));
  const std::string plan = d.file("p.plan");
  // The same engines named from another folder are the same engines: the same plan.
  std::filesystem::create_directories(d.path / "sub");
  const std::string again =
      d.write("sub/s.toml", "scenes = [\"" + std::string(DROPCHECK_SOURCE_DIR) +
                                "/scenarios/free_fall_drag.toml\"]\n"
                                "engines = [\"ours-f64\", \"../good.toml\", \"" +
                                hang +
                                "\", \"../crash.toml\"]\n"
                                "[[axis]]\nname = \"timestep\"\nvalues = [\"1/120\", \"1/60\"]\n");
  const Cli q = run_sweep_cli({"plan", again, "--out", d.file("q.plan"), "--keys"});
  REQUIRE(q.code == 0);
  CHECK(q.out.substr(q.out.find('\n')) == p.out.substr(p.out.find('\n')));
  // The plan alone never starts them.
  const Cli alone = run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("a")});
  CHECK(alone.code == 2);
  CHECK_THAT(alone.err, Contains("runs the external engine steady@") &&
                            Contains("a plan never starts a program by itself"));
  CHECK(!std::filesystem::exists(d.file("a/shard-1-of-1.jsonl")));
  // Given, they run: the hanging and the dying engine's cells are their records, the rest ok.
  const Cli ran =
      run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("b"), "--engine-file", good,
                     "--engine-file", hang, "--engine-file", crash, "--quiet"});
  REQUIRE(ran.code == 0);
  CHECK_THAT(ran.out, Contains("8 cells (4 ok, 4 not ok, 0 skipped)"));
  const std::string records = slurp(d.file("b/shard-1-of-1.jsonl"));
  // The hang is an engine error (no answer within its engine file's 2 s), the death a crash.
  CHECK_THAT(records, Contains("\"status\":\"engine-error\",\"reason\":\"at step 3: no") &&
                          Contains("\"status\":\"crashed\",\"reason\":\"at step 3"));
  // A changed engine file is another engine: refused, naming both fingerprints.
  std::ofstream(good, std::ios::app) << "# edited\n";
  const Cli changed =
      run_sweep_cli({"sweep", plan, "--shard", "1/1", "--out", d.file("c"), "--engine-file", good,
                     "--engine-file", hang, "--engine-file", crash});
  CHECK(changed.code == 2);
  CHECK_THAT(changed.err, Contains("changed since `dropcheck plan`") && Contains("steady@"));
  // A plan's external engine id is data: one that is not NAME@16 hex digits is refused for what it
  // is, before its hash is looked at.
  std::string text = slurp(plan);
  for (std::size_t at = 0; (at = text.find("\"steady@", at)) != std::string::npos; ++at)
    text.replace(at, 8, "\"steady:");
  const Cli forged =
      run_sweep_cli({"sweep", d.write("bad.plan", text), "--shard", "1/1", "--out", d.file("d")});
  CHECK(forged.code == 2);
  CHECK_THAT(forged.err, Contains("unknown engine 'steady:"));
}
