// XML 1.0 text, escaped once for every XML dropcheck writes: `check --junit` (harness/report/
// verdict_files.hpp), the model MuJoCo reads (adapters/mujoco.cpp), whose names are free text, and
// the text the report's HTML page adds to what cmark-gfm renders (harness/report/report_html.cpp).
#pragma once

#include <string>

namespace dropcheck {

// `s` as XML 1.0 text, for an element or an attribute value: the five markup characters as
// entities, tab, newline and carriage return as character references (an attribute would turn them
// into spaces), and what XML 1.0 cannot carry (another control character, a byte that is not part
// of valid UTF-8, U+FFFE, U+FFFF) as U+FFFD.
std::string xml_escape(const std::string& s);

}  // namespace dropcheck
