// InputError: bad input (a scene file, a flag) named precisely enough to fix: file, key, problem.
// The CLI prints what() and exits with code 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dropcheck {

struct InputError : std::runtime_error {
  // Renders "FILE:LINE: KEY: PROBLEM", leaving out the parts that are empty or zero.
  InputError(const std::string& file, int line, const std::string& key, const std::string& problem);
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Longest excerpt of an input quoted in a message, in bytes of the input (kExcerptBytes).
inline constexpr std::size_t kExcerptBytes = 60;

// A piece of input text quoted for a message: single-quoted, at most kExcerptBytes of it, with
// every byte that could act on a terminal or is not UTF-8 written as \xNN (C0 controls, DEL, C1
// controls, a stray or truncated UTF-8 sequence), and a longer text cut with "... (N bytes)". So a
// message never carries more than a short, inert excerpt of what it could not parse.
std::string excerpt(std::string_view text, std::size_t max_bytes = kExcerptBytes);

// The offset of the first byte excerpt() would escape, other than tab, line feed and carriage
// return; npos when there is none (the text is UTF-8 with no control character).
std::size_t find_unsafe_byte(std::string_view text);

// The same for one line of text that is printed as a name or a field: tab, line feed and carriage
// return count as unsafe too. npos when the text is inert on a terminal.
std::size_t find_unsafe_in_line(std::string_view text);

// `text` with the same escapes as excerpt() but whole and unquoted: for a name an engine announced
// or a line it wrote to stderr, printed to a terminal.
std::string escape_controls(std::string_view text);

}  // namespace dropcheck
