// Tests the report's HTML page (harness/report/report_html.cpp): the Markdown's numbers as
// cmark-gfm renders them, hostile text never rendered as HTML, the anchors the Markdown links to,
// plots embedded and never read through a link. The page in a browser: ctest report.html_browser.
#include "harness/report/report_html.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "../test_dirs.hpp"
#include "harness/report/report_format.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

std::optional<std::string> no_plot(const std::string&) {
  return std::nullopt;
}

}  // namespace

TEST_CASE("The HTML page renders the Markdown's tables and numbers, with the anchors it links to",
          "[report][html]") {
  const std::string md =
      "# r\n\n## Summary\n\n| scene | error ode | verdict |\n|---|---:|---|\n"
      "| [drop](#drop_2) | 3.67 cm | [ok](#drop_2) |\n\n## Scenes\n\n### drop_2\n\ntext\n\n"
      "### drop_2\n\nagain\n";
  const std::string html = report_html(md, "t", no_plot);
  CHECK_THAT(
      html, Contains("<td align=\"right\">3.67 cm</td>") && Contains("<a href=\"#drop_2\">ok</a>"));
  // Each h2 and h3 gets the anchor of the Markdown's links; a repeated one is numbered.
  CHECK_THAT(html, Contains("<h2 id=\"summary\">Summary</h2>") &&
                       Contains("<h3 id=\"drop_2\">drop_2</h3>") &&
                       Contains("<h3 id=\"drop_2-1\">drop_2</h3>"));
  // The navigation lists the sections, and the scenes under theirs.
  CHECK_THAT(html, Contains("<li><a href=\"#scenes\">Scenes</a></li>\n<li><ul>\n"
                            "<li><a href=\"#drop_2\">drop_2</a></li>"));
  // Nothing is fetched: the page forbids every source but its own inline style and script.
  CHECK_THAT(html, Contains("default-src 'none'; img-src data:"));
}

TEST_CASE("Text a scene or an engine supplied is never rendered as HTML in the page",
          "[report][html][hostile]") {
  const std::string md =
      "## A <script>alert(1)</script> scene\n\n<img src=x onerror=alert(2)>\n\n"
      "[click](javascript:alert(3)) and ![p](data:image/svg+xml;base64,PHN2Zz4=)\n\n"
      "| engine | note |\n|---|---|\n| <b onmouseover=alert(4)>e</b> | \"quoted\" & more |\n";
  const std::string html = report_html(md, "<title>", no_plot);
  CHECK_THAT(html, !Contains("<script>alert") && !Contains("onerror") && !Contains("onmouseover") &&
                       !Contains("javascript:") && !Contains("data:image/svg+xml;base64,PHN2Zz4="));
  CHECK_THAT(html, Contains("<title>&lt;title&gt;</title>"));
  // One script element: the page's own.
  std::size_t scripts = 0;
  for (std::size_t at = 0; (at = html.find("<script", at)) != std::string::npos; ++at) ++scripts;
  CHECK(scripts == 1);
}

TEST_CASE("A plot of the report folder is embedded; a link or a path is not followed",
          "[report][html][hostile]") {
  ScratchDir d("report-html");
  const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"/>";
  d.write("a.svg", svg);
  d.write("secret.txt", "SECRET");
  std::filesystem::create_symlink(d.file("secret.txt"), d.file("b.svg"));
  const std::string md =
      "![a](a.svg) ![b](b.svg) ![c](../c.svg) ![d](missing.svg)\n\nx = m*g*h, **bold**\n";
  write_report_html(d.path.string(), literal_stars(md), "t");
  const std::string html = slurp(d.file("index.html"));
  // The SVG's bytes percent-encoded: no quote, angle bracket or space left in the attribute.
  CHECK_THAT(html, Contains("<img src=\"data:image/svg+xml,%3Csvg%20xmlns=%22http://www.w3.org/"
                            "2000/svg%22/%3E\""));
  CHECK_THAT(html, Contains("src=\"b.svg\"") && Contains("src=\"../c.svg\"") &&
                       Contains("src=\"missing.svg\"") && !Contains("SECRET"));
  // Products stay products, bold stays bold.
  CHECK_THAT(html, Contains("x = m*g*h, <strong>bold</strong>"));
}
