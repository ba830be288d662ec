// Scene text made safe for toml++ 3.3.0 before it is parsed. That version's Unicode tables reach
// __builtin_unreachable for some non-ASCII code points (U+00A1..U+0499, U+2C4E..U+3047 but U+3000,
// U+FBF6..U+FEFE) whenever it asks whether one is whitespace, and it asks that of valid TOML too:
// the first character after a line-ending backslash in a """ string (s = """\<newline>é""") is
// undefined behaviour. So toml++ is only ever given ASCII, and the document keeps its meaning:
// - a non-ASCII character in a "..." or """...""" string becomes its \uXXXX or \UXXXXXXXX escape;
// - a '...' or '''...''' string holding one becomes the same text as a "..." or """...""" string;
// - in a comment it becomes '?' (a comment has no value);
// - anywhere else TOML 1.0 never allows one (keys, whitespace and values outside strings are
//   ASCII), so it is refused here, as are invalid UTF-8 and control characters other than tab,
//   line feed and carriage return (TOML allows no others anywhere). Line numbers are unchanged.
#pragma once

#include <string>

namespace dropcheck {

// `text` with every non-ASCII character rewritten as above (the same text when it is all ASCII;
// a leading UTF-8 byte order mark is dropped). Throws InputError naming `path`, the line and the
// problem (invalid UTF-8, a control character, a non-ASCII character outside a string or comment,
// a backslash before a non-ASCII character, a string left open at the end of its line).
std::string toml_as_ascii(const std::string& text, const std::string& path);

}  // namespace dropcheck
