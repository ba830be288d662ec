// Tests that user text never becomes gnuplot code (harness/report/plot.cpp): hostile scene, body
// and label text runs gnuplot for real, and a marker file that an injected command would create
// must not exist afterwards; plus the text sanitiser on its own.
#include "harness/report/plot.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../test_dirs.hpp"
#include "harness/cli/cli.hpp"
#include "tests/harness/report/has_gnuplot.hpp"

using namespace dropcheck;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;
namespace fs = std::filesystem;

namespace {

// Titles that would run `touch MARKER` if any part of them were read as gnuplot code.
std::vector<std::string> hostile_titles(const std::string& marker) {
  return {
      "a\n`touch " + marker + "`",
      "b\nsystem(\"touch " + marker + "\")",
      "c'\n`touch " + marker + "`\n'",
      "d'; system('touch " + marker + "'); print '",
      "e\"`touch " + marker + "`\"",
      std::string("f\0\n!touch ", 11) + marker,
      "g\r\nset output '" + marker + "'\nplot 1",
      "h\\\n`touch " + marker + "`",
  };
}

PlotSpec spec_with(const std::string& text) {
  PlotSpec p;
  p.title = p.xlabel = p.ylabel = text;
  PlotSeries s;
  s.title = text;
  s.x = {1.0, 2.0};
  s.y = {1.0, 4.0};
  s.labels = {text, "\"" + text};
  p.series.push_back(s);
  return p;
}

}  // namespace

TEST_CASE("plot text turns control characters into spaces, bad UTF-8 into '?' and cuts long text",
          "[plot]") {
  CHECK(plot_text("a\nb\rc\td") == "a b c d");
  CHECK(plot_text(std::string("x\0y", 3)) == "x y");
  CHECK(plot_text("caf\xc3\xa9") == "caf\xc3\xa9");  // valid UTF-8 stays
  CHECK(plot_text("bad\xff\xc3(") ==
        "bad?"
        "?(");                                // stray and truncated bytes
  CHECK(plot_text("\xc0\xaf") == "??");       // overlong '/'
  CHECK(plot_text("\xed\xa0\x80") == "???");  // a UTF-16 surrogate
  const std::string mb(1 << 20, 'x');
  CHECK(plot_text(mb) == std::string(kPlotTextMax, 'x') + "...");
}

TEST_CASE("no character of a title can end a gnuplot string or start a command", "[plot]") {
  const std::string plain = gnuplot_script(spec_with("x"), "d.dat", "p.svg");
  for (const std::string& t : hostile_titles("/tmp/never")) {
    const std::string script = gnuplot_script(spec_with(t), "d.dat", "p.svg");
    // Every line of the script is one command: the text never adds a line.
    CHECK(std::count(script.begin(), script.end(), '\n') ==
          std::count(plain.begin(), plain.end(), '\n'));
    CHECK(script.find('\0') == std::string::npos);
  }
}

TEST_CASE("gnuplot runs no command written in a title, label or legend", "[plot]") {
  if (!has_gnuplot()) {
    WARN("gnuplot is not installed: nothing to test");
    return;
  }
  ScratchDir dir("plot-inject");
  const std::string marker = dir.file("MARKER");
  for (const std::string& t : hostile_titles(marker)) {
    INFO(t);
    CHECK(render_plot(spec_with(t), dir.path.string(), "p.svg") == "");
    CHECK_FALSE(fs::exists(marker));
    CHECK(fs::exists(dir.file("p.svg")));
  }
  // 1 MB of text and invalid UTF-8: drawn, cut, and the SVG stays valid UTF-8.
  CHECK(render_plot(spec_with(std::string(1 << 20, 'y') + "\xff\xfe"), dir.path.string(),
                    "big.svg") == "");
  const std::string svg = slurp(dir.file("big.svg"));
  CHECK(svg.find(std::string(kPlotTextMax, 'y') + "...") != std::string::npos);
  CHECK(svg.find(std::string(kPlotTextMax + 1, 'y')) == std::string::npos);
  CHECK(svg.find('\xff') == std::string::npos);
}

TEST_CASE("dropcheck report on a scene whose names hold commands runs none of them",
          "[plot][report]") {
  if (!has_gnuplot()) {
    WARN("gnuplot is not installed: nothing to test");
    return;
  }
  ScratchDir dir("report-inject");
  const std::string marker = dir.file("MARKER");
  // TOML basic strings: \u0060 is a backtick, \n a newline (allowed in a description only: a
  // control character in a name is refused at load, scene_loader_test).
  const std::string scene = dir.file("hostile.toml");
  {
    std::ofstream(scene)
        << "name = \"x \\u0060touch " << marker << "\\u0060 system('touch " << marker << "')\"\n"
        << "description = \"d\\n`touch " << marker << "`\"\n"
        << "duration = 0.5\ntimestep = \"1/60\"\ntimesteps = [\"1/30\", \"1/60\"]\n"
        << "[world]\ngravity = [0.0, -9.8, 0.0]\n"
        << "[[body]]\nname = \"b `touch " << marker << "`\"\n"
        << "position = [0.0, 10.0, 0.0]\n"
        << "[[body]]\nname = \"c';system('touch " << marker << "');'\"\n"
        << "position = [3.0, 10.0, 0.0]\n";
  }
  std::ostringstream out, err;
  const int rc = cli_main({"report", scene, "--out", dir.file("out"), "--no-timing", "--engine",
                           "ours", "--engine", "ours-f64"},
                          out, err);
  INFO(err.str());
  CHECK(rc == kExitOk);
  CHECK_FALSE(fs::exists(marker));
  bool svg = false;
  for (const fs::directory_entry& e : fs::directory_iterator(dir.file("out")))
    svg = svg || e.path().extension() == ".svg";
  CHECK(svg);
}
