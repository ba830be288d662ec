// The report as one HTML page beside its Markdown (DIR/index.html): the Markdown is the one source
// of its numbers, rendered by Debian's cmark-gfm (GitHub tables; safe mode, so raw HTML in any text
// a scene or an engine supplied is dropped, never rendered); its headings given the anchors the
// Markdown links to; a navigation by section and scene; each plot the report folder holds
// embedded as a data: URI, so the page is one offline file that fetches nothing; and a short
// script of its own: every table sorts by a click on a column, and a filter shows one engine.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace dropcheck {

// The page of `markdown`. `read_plot(file)` gives the bytes of an image the Markdown names by a
// plain file name (an SVG of the report folder), or nullopt: such an image is left as a link.
std::string report_html(
    const std::string& markdown, const std::string& title,
    const std::function<std::optional<std::string>(const std::string&)>& read_plot);

// Writes DIR/index.html from `markdown`, the plots read from DIR (regular files only, never
// through a link).
void write_report_html(const std::string& dir, const std::string& markdown,
                       const std::string& title);

}  // namespace dropcheck
