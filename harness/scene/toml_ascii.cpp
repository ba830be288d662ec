#include "harness/scene/toml_ascii.hpp"

#include <cstdio>

#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

// Decodes the UTF-8 sequence at text[i]: its code point and length, or length 0 when it is not
// valid UTF-8 (truncated, a stray continuation byte, overlong, a surrogate, above U+10FFFF).
struct CodePoint {
  unsigned value = 0;
  std::size_t length = 0;
};

CodePoint decode(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return {c, 1};
  std::size_t n = 0;
  unsigned cp = 0, min = 0;
  if ((c & 0xE0) == 0xC0)
    n = 2, cp = c & 0x1Fu, min = 0x80;
  else if ((c & 0xF0) == 0xE0)
    n = 3, cp = c & 0x0Fu, min = 0x800;
  else if ((c & 0xF8) == 0xF0)
    n = 4, cp = c & 0x07u, min = 0x10000;
  else
    return {};
  if (i + n > text.size()) return {};
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return {};
    cp = (cp << 6) | (byte(i + k) & 0x3Fu);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return {};
  return {cp, n};
}

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*X", digits, v);
  return buf;
}

// "U+00E9".
std::string code_name(unsigned cp) {
  return "U+" + hex(cp, 4);
}

// The TOML escape of a code point: \uXXXX, or \UXXXXXXXX above U+FFFF.
std::string escape(unsigned cp) {
  return cp <= 0xFFFF ? "\\u" + hex(cp, 4) : "\\U" + hex(cp, 8);
}

// One pass over the text: where each character is (outside, in a comment, in one of the four
// string kinds) decides what toml++ gets for it.
class Rewriter {
 public:
  Rewriter(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  std::string run() {
    check_bytes();
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;  // the byte order mark toml++ skips
    while (i_ < text_.size()) outside();
    return out_;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_, line_at(i_), "", problem);
  }

  int line_at(std::size_t pos) const {
    int line = 1;
    for (std::size_t k = 0; k < pos && k < text_.size(); ++k) line += text_[k] == '\n';
    return line;
  }

  // Invalid UTF-8 and control characters are refused wherever they are, before anything else.
  void check_bytes() {
    for (std::size_t k = 0; k < text_.size();) {
      const CodePoint c = decode(text_, k);
      i_ = k;
      if (c.length == 0)
        fail("not valid UTF-8 (byte 0x" + hex(static_cast<unsigned char>(text_[k]), 2) +
             "); a scene file is UTF-8 text");
      if ((c.value < 0x20 && c.value != '\t' && c.value != '\n' && c.value != '\r') ||
          c.value == 0x7F)
        fail("control character " + code_name(c.value) + "; TOML allows only tab and line breaks");
      k += c.length;
    }
    i_ = 0;
  }

  bool at(const char* s) const {
    return text_.compare(i_, std::char_traits<char>::length(s), s) == 0;
  }
  bool ascii() const { return static_cast<unsigned char>(text_[i_]) < 0x80; }
  void copy(std::size_t n = 1) {
    out_.append(text_, i_, n);
    i_ += n;
  }

  void outside() {
    if (!ascii())
      fail("character " + code_name(decode(text_, i_).value) +
           " outside a string or comment; TOML allows non-ASCII text only in strings and comments");
    if (text_[i_] == '#') return comment();
    if (at("\"\"\"")) return multi_line_basic();
    if (text_[i_] == '"') return basic();
    if (at("'''")) return multi_line_literal();
    if (text_[i_] == '\'') return literal();
    copy();
  }

  void comment() {
    while (i_ < text_.size() && text_[i_] != '\n') {
      if (ascii()) {
        copy();
      } else {
        out_ += '?';
        i_ += decode(text_, i_).length;
      }
    }
  }

  // A non-ASCII character of a "..." or """...""" string: its escape. After a backslash it would
  // be an invalid escape that the rewrite must not turn into a valid one.
  void string_character(bool escaped) {
    const CodePoint c = decode(text_, i_);
    if (escaped) fail("a backslash before " + code_name(c.value) + " is not a TOML escape");
    out_ += escape(c.value);
    i_ += c.length;
  }

  void basic() {
    copy();  // "
    bool escaped = false;
    for (;;) {
      if (i_ >= text_.size() || text_[i_] == '\n')
        fail("a \"...\" string is not closed on its line");
      if (!ascii()) {
        string_character(escaped);
      } else {
        const char c = text_[i_];
        copy();
        if (!escaped && c == '"') return;
        escaped = !escaped && c == '\\';
        continue;
      }
      escaped = false;
    }
  }

  void multi_line_basic() {
    copy(3);
    bool escaped = false;
    while (i_ < text_.size()) {
      if (!ascii()) {
        string_character(escaped);
        escaped = false;
        continue;
      }
      if (!escaped && at("\"\"\"")) {  // the closing run (up to two more quotes are content)
        while (i_ < text_.size() && text_[i_] == '"') copy();
        return;
      }
      const char c = text_[i_];
      copy();
      escaped = !escaped && c == '\\';
    }
  }

  // A literal string's text as the body of a basic string with the same value.
  static std::string as_basic(const std::string& body) {
    std::string out;
    for (std::size_t k = 0; k < body.size();) {
      const CodePoint c = decode(body, k);
      if (c.value == '\\' || c.value == '"')
        out += std::string("\\") + body[k];
      else if (c.value < 0x80)
        out += body[k];
      else
        out += escape(c.value);
      k += c.length;
    }
    return out;
  }

  static bool all_ascii(const std::string& s) {
    for (char c : s)
      if (static_cast<unsigned char>(c) >= 0x80) return false;
    return true;
  }

  void literal() {
    const std::size_t end = text_.find_first_of("'\n", i_ + 1);
    if (end == std::string::npos || text_[end] == '\n')
      fail("a '...' string is not closed on its line");
    const std::string body = text_.substr(i_ + 1, end - i_ - 1);
    out_ += all_ascii(body) ? "'" + body + "'" : "\"" + as_basic(body) + "\"";
    i_ = end + 1;
  }

  void multi_line_literal() {
    const std::size_t end = text_.find("'''", i_ + 3);
    if (end == std::string::npos) {  // unclosed: toml++ says so, given ASCII
      if (!all_ascii(text_.substr(i_))) fail("a '''...''' string is not closed");
      return copy(text_.size() - i_);
    }
    std::size_t run_end = end;
    while (run_end < text_.size() && text_[run_end] == '\'') ++run_end;
    // Up to two quotes before the closing ''' belong to the text.
    const std::string body = text_.substr(i_ + 3, run_end - 3 - (i_ + 3));
    if (run_end - end > 5 && !all_ascii(body))
      fail("a '''...''' string ends in more than five quotes");
    if (all_ascii(body))
      out_.append(text_, i_, run_end - i_);  // as written (more than five quotes: toml++ refuses)
    else
      out_ += "\"\"\"" + as_basic(body) + "\"\"\"";
    i_ = run_end;
  }

  const std::string& text_;
  const std::string& path_;
  std::size_t i_ = 0;
  std::string out_;
};

}  // namespace

std::string toml_as_ascii(const std::string& text, const std::string& path) {
  return Rewriter(text, path).run();
}

}  // namespace dropcheck
