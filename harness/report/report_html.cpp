#include "harness/report/report_html.hpp"

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm.h>

#include <filesystem>
#include <memory>
#include <set>
#include <vector>

#include "harness/io/atomic_file.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/xml_text.hpp"
#include "harness/report/report_scene.hpp"

namespace dropcheck {
namespace {

// The Markdown as HTML: CommonMark with GitHub's tables, in cmark's safe mode (the default: raw
// HTML is replaced by a comment, and javascript:, vbscript:, file: and data: links are emptied).
std::string markdown_html(const std::string& markdown) {
  cmark_gfm_core_extensions_ensure_registered();
  const std::unique_ptr<cmark_parser, decltype(&cmark_parser_free)> parser(
      cmark_parser_new(CMARK_OPT_DEFAULT), cmark_parser_free);
  cmark_parser_attach_syntax_extension(parser.get(), cmark_find_syntax_extension("table"));
  cmark_parser_feed(parser.get(), markdown.data(), markdown.size());
  const std::unique_ptr<cmark_node, decltype(&cmark_node_free)> doc(
      cmark_parser_finish(parser.get()), cmark_node_free);
  char* html = cmark_render_html(doc.get(), CMARK_OPT_DEFAULT,
                                 cmark_parser_get_syntax_extensions(parser.get()));
  std::string out(html);
  cmark_get_default_mem_allocator()->free(html);
  return out;
}

// The text of an HTML fragment: tags dropped, cmark's five entities turned back.
std::string text_of(const std::string& html) {
  std::string text;
  bool in_tag = false;
  for (char c : html) {
    if (c == '<') in_tag = true;
    if (!in_tag) text += c;
    if (c == '>') in_tag = false;
  }
  for (const auto& [entity, c] :
       {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}})
    for (std::size_t at = 0; (at = text.find(entity, at)) != std::string::npos; ++at)
      text.replace(at, std::string(entity).size(), c);
  return text;
}

struct Heading {
  int level = 2;
  std::string id, text;
};

// Gives each <h2> and <h3> the anchor the Markdown links to (report_scene.hpp: heading_anchor; a
// repeated one numbered -1, -2, ... as GitHub numbers them), and lists them for the navigation.
std::vector<Heading> anchor_headings(std::string& html) {
  std::vector<Heading> out;
  std::set<std::string> used;
  for (std::size_t at = 0; (at = html.find("<h", at)) != std::string::npos; ++at) {
    const char level = at + 3 < html.size() ? html[at + 2] : '\0';
    if ((level != '2' && level != '3') || html[at + 3] != '>') continue;
    const std::string close = std::string("</h") + level + ">";
    const std::size_t end = html.find(close, at);
    if (end == std::string::npos) break;
    Heading h{level - '0', "", text_of(html.substr(at + 4, end - at - 4))};
    h.id = heading_anchor(h.text);
    for (int n = 1; !used.insert(h.id).second; ++n)
      h.id = heading_anchor(h.text) + "-" + std::to_string(n);
    const std::string open = std::string("<h") + level + " id=\"" + h.id + "\">";
    html.replace(at, 4, open);
    out.push_back(std::move(h));
  }
  return out;
}

// `bytes` as the data of a data: URI: letters, digits and -_.~!*();:@=+,/ as they are, every other
// byte as %XX. An SVG's text stays text (it compresses as well as the plot file does), and no
// quote, ampersand, angle bracket or white space reaches the attribute.
std::string percent_encoded(const std::string& bytes) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  static constexpr std::string_view kKept = "-_.~!*();:@=+,/";
  std::string out;
  out.reserve(bytes.size() + bytes.size() / 4);
  for (const char c : bytes) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') ||
        kKept.find(c) != std::string_view::npos) {
      out += c;
    } else {
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return out;
}

// Each <img src="FILE.svg"> of a plain file name that `read_plot` gives turned into a data: URI,
// the page copied once into a new string (a plot is large: no replace inside the page).
void embed_plots(std::string& html,
                 const std::function<std::optional<std::string>(const std::string&)>& read_plot) {
  static const std::string kSrc = "<img src=\"";
  std::string out;
  std::size_t copied = 0;
  for (std::size_t at = 0; (at = html.find(kSrc, at)) != std::string::npos; ++at) {
    const std::size_t from = at + kSrc.size(), end = html.find('"', from);
    if (end == std::string::npos) break;
    const std::string file = html.substr(from, end - from);
    if (!file.ends_with(".svg") || file.find_first_of("/\\:&%") != std::string::npos) continue;
    const std::optional<std::string> svg = read_plot(file);
    if (!svg) continue;
    out.append(html, copied, from - copied);
    out += "data:image/svg+xml," + percent_encoded(*svg);
    copied = end;
  }
  out.append(html, copied, std::string::npos);
  html = std::move(out);
}

// The navigation: every section, and under "Scenes" every scene.
std::string navigation(const std::vector<Heading>& headings) {
  std::string nav = "<nav>\n<p><strong>Sections</strong></p>\n<ul>\n";
  bool open = false;
  for (const Heading& h : headings) {
    if (h.level == 2 && open) {
      nav += "</ul></li>\n";
      open = false;
    }
    if (h.level == 3 && !open) {
      nav += "<li><ul>\n";
      open = true;
    }
    nav += "<li><a href=\"#" + h.id + "\">" + xml_escape(h.text) + "</a></li>\n";
  }
  return nav + (open ? "</ul></li>\n" : "") + "</ul>\n</nav>\n";
}

// The page's style and script, written here and nowhere else. The script: a click on a column
// header sorts its table (numbers by value, a length by its unit: 3 mm before 2 cm; "—" and text
// after numbers; a second click reverses), and the engine filter shows one engine's rows and
// "error ENGINE" columns in every table.
constexpr const char* kStyle = R"(body{font-family:sans-serif;margin:0;display:flex}
nav{position:sticky;top:0;height:100vh;overflow:auto;min-width:14em;padding:0 1em;background:#f4f4f4;font-size:90%}
nav ul{list-style:none;padding-left:0.8em}main{padding:0 1.5em;max-width:110em;overflow-x:auto}
table{border-collapse:collapse;margin:1em 0;font-size:85%}th,td{border:1px solid #ccc;padding:2px 6px}
th{background:#eee;cursor:pointer}th[aria-sort=ascending]::after{content:" \25B2"}
th[aria-sort=descending]::after{content:" \25BC"}img{max-width:100%}
#filter{position:sticky;top:0;background:#fff;padding:0.5em 0;border-bottom:1px solid #ccc}
)";

constexpr const char* kScript = R"((function () {
  "use strict";
  var units = {m: 1, cm: 1e-2, mm: 1e-3, um: 1e-6, nm: 1e-9};
  function key(text) {
    var t = text.trim().replace(/^[+]/, "");
    var m = /^(-?\d*\.?\d+(?:e[-+]?\d+)?)\s*([a-z%]*)/i.exec(t);
    if (!m) return {num: false, v: t.toLowerCase()};
    return {num: true, v: parseFloat(m[1]) * (units[m[2]] || 1)};
  }
  function compare(a, b) {
    if (a.num !== b.num) return a.num ? -1 : 1;
    return a.v < b.v ? -1 : a.v > b.v ? 1 : 0;
  }
  function sortable(table) {
    if (!table.tHead || !table.tBodies.length) return;
    var heads = table.tHead.rows[0].cells, body = table.tBodies[0];
    Array.prototype.forEach.call(body.rows, function (r, i) { r.dataset.order = i; });
    Array.prototype.forEach.call(heads, function (th, col) {
      th.title = "sort by this column";
      th.addEventListener("click", function () {
        var dir = th.getAttribute("aria-sort") === "ascending" ? -1 : 1;
        Array.prototype.forEach.call(heads, function (h) { h.removeAttribute("aria-sort"); });
        th.setAttribute("aria-sort", dir > 0 ? "ascending" : "descending");
        var rows = Array.prototype.slice.call(body.rows);
        rows.sort(function (a, b) {
          return dir * compare(key(a.cells[col].textContent), key(b.cells[col].textContent)) ||
                 a.dataset.order - b.dataset.order;
        });
        rows.forEach(function (r) { body.appendChild(r); });
      });
    });
  }
  function show(engine) {
    Array.prototype.forEach.call(document.querySelectorAll("main table"), function (table) {
      if (!table.tHead) return;
      var heads = table.tHead.rows[0].cells, hidden = [];
      Array.prototype.forEach.call(heads, function (th, col) {
        var m = /^error (\S+)$/.exec(th.textContent.trim());
        hidden[col] = engine !== "" && m !== null && m[1] !== engine;
      });
      var byEngine = heads.length && heads[0].textContent.trim() === "engine";
      Array.prototype.forEach.call(table.rows, function (row, r) {
        Array.prototype.forEach.call(row.cells, function (cell, col) {
          cell.hidden = hidden[col] === true;
        });
        if (r > 0 && byEngine) row.hidden = engine !== "" && row.cells[0].textContent.trim() !== engine;
      });
    });
  }
  var tables = document.querySelectorAll("main table");
  Array.prototype.forEach.call(tables, sortable);
  var select = document.getElementById("engine");
  var summary = tables.length ? tables[0] : null;
  if (summary && summary.tHead)
    Array.prototype.forEach.call(summary.tHead.rows[0].cells, function (th) {
      var m = /^error (\S+)$/.exec(th.textContent.trim());
      if (m) select.add(new Option(m[1], m[1]));
    });
  select.addEventListener("change", function () { show(select.value); });
})();
)";

}  // namespace

std::string report_html(
    const std::string& markdown, const std::string& title,
    const std::function<std::optional<std::string>(const std::string&)>& read_plot) {
  std::string body = markdown_html(markdown);
  const std::vector<Heading> headings = anchor_headings(body);
  embed_plots(body, read_plot);
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
         "img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n<title>" +
         xml_escape(title) + "</title>\n<style>\n" + kStyle + "</style>\n</head>\n<body>\n" +
         navigation(headings) +
         "<main>\n<div id=\"filter\"><label>Engine: <select id=\"engine\"><option value=\"\">all "
         "engines</option></select></label> (click a column header to sort its table)</div>\n" +
         body + "</main>\n<script>\n" + kScript + "</script>\n</body>\n</html>\n";
}

void write_report_html(const std::string& dir, const std::string& markdown,
                       const std::string& title) {
  const auto read_plot = [&](const std::string& file) -> std::optional<std::string> {
    const std::filesystem::path p = std::filesystem::path(dir) / file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(p, ec))) return {};
    return read_regular_file(p.string(), 64LL << 20, "64 MiB, for a plot", Links::refuse);
  };
  write_file_atomic((std::filesystem::path(dir) / "index.html").string(),
                    report_html(markdown, title, read_plot));
}

}  // namespace dropcheck
