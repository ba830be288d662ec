#include "harness/core/input_error.hpp"

#include <algorithm>

namespace dropcheck {
namespace {

// Length of the valid UTF-8 sequence at text[i] that is not a C1 control (U+0080..U+009F), or 0.
std::size_t printable_utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  std::size_t n = 0;
  if (b >= 0xc2 && b <= 0xdf)
    n = 2;
  else if (b >= 0xe0 && b <= 0xef)
    n = 3;
  else if (b >= 0xf0 && b <= 0xf4)
    n = 4;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  // Overlong, surrogate and beyond-U+10FFFF forms, and the C1 controls (C2 80..C2 9F).
  if (b == 0xc2 && byte(i + 1) < 0xa0) return 0;
  if (b == 0xe0 && byte(i + 1) < 0xa0) return 0;
  if (b == 0xed && byte(i + 1) >= 0xa0) return 0;
  if (b == 0xf0 && byte(i + 1) < 0x90) return 0;
  if (b == 0xf4 && byte(i + 1) >= 0x90) return 0;
  return n;
}

// Appends text[0, to) with every unsafe byte as \xNN; a multi-byte character is kept whole or
// escaped whole, never split.
void append_escaped(std::string& out, std::string_view text, std::size_t to) {
  static const char* hex = "0123456789abcdef";
  for (std::size_t i = 0; i < to;) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b >= 0x20 && b < 0x7f) {
      out += static_cast<char>(b);
      ++i;
    } else if (const std::size_t n = b >= 0x80 ? printable_utf8_length(text, i) : 0; n > 0) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      out += "\\x";
      out += hex[b >> 4];
      out += hex[b & 0xf];
      ++i;
    }
  }
}

std::string render(const std::string& file, int line, const std::string& key,
                   const std::string& problem) {
  // Appended piece by piece: g++ 12 -O3 warns (-Wstringop-overflow, a false positive) on
  // ":" + std::to_string(line).
  std::string out = file;
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  if (!out.empty()) out += ": ";
  if (!key.empty()) {
    out += key;
    out += ": ";
  }
  out += problem;
  return out;
}

}  // namespace

std::string excerpt(std::string_view text, std::size_t max_bytes) {
  std::size_t cut = std::min(text.size(), max_bytes);
  while (cut < text.size() && cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80)
    --cut;  // do not cut a UTF-8 character in two
  std::string out = "'";
  append_escaped(out, text, cut);
  out += '\'';
  if (cut < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::size_t find_unsafe_byte(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if ((b >= 0x20 && b < 0x7f) || b == '\t' || b == '\n' || b == '\r') {
      ++i;
      continue;
    }
    const std::size_t n = b >= 0x80 ? printable_utf8_length(text, i) : 0;
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

std::size_t find_unsafe_in_line(std::string_view text) {
  return std::min(find_unsafe_byte(text), text.find_first_of("\t\r\n"));
}

std::string escape_controls(std::string_view text) {
  std::string out;
  append_escaped(out, text, text.size());
  return out;
}

InputError::InputError(const std::string& file, int line, const std::string& key,
                       const std::string& problem)
    : std::runtime_error(render(file, line, key, problem)) {}

}  // namespace dropcheck
