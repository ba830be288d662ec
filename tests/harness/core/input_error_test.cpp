#include "harness/core/input_error.hpp"

#include <catch2/catch.hpp>
#include <string>

using namespace dropcheck;

TEST_CASE("InputError renders file, line, key and problem, leaving out the empty parts",
          "[input_error]") {
  CHECK(std::string(InputError("a.toml", 3, "mass", "must be > 0").what()) ==
        "a.toml:3: mass: must be > 0");
  CHECK(std::string(InputError("a.toml", 0, "", "empty").what()) == "a.toml: empty");
}

TEST_CASE("excerpt quotes short text as it is", "[input_error]") {
  CHECK(excerpt("1.5e3x") == "'1.5e3x'");
  CHECK(excerpt("") == "''");
  CHECK(excerpt("caf\xc3\xa9") == "'caf\xc3\xa9'");  // UTF-8 text is kept
}

TEST_CASE("excerpt escapes every byte that could act on a terminal", "[input_error]") {
  CHECK(excerpt("\x1b]0;owned\x07") == "'\\x1b]0;owned\\x07'");
  CHECK(excerpt(std::string("a\0b", 3)) == "'a\\x00b'");
  CHECK(excerpt("\x7f\t\r\n") == "'\\x7f\\x09\\x0d\\x0a'");
  CHECK(excerpt("\xc2\x9b"
                "31m") == "'\\xc2\\x9b31m'");  // C1 CSI, as UTF-8
  CHECK(excerpt("\x9b"
                "31m") == "'\\x9b31m'");                  // C1 CSI, a raw byte
  CHECK(excerpt("\xc3") == "'\\xc3'");                    // a truncated sequence
  CHECK(excerpt("\xed\xa0\x80") == "'\\xed\\xa0\\x80'");  // a UTF-16 surrogate
  CHECK(excerpt("\xc0\xaf") == "'\\xc0\\xaf'");           // an overlong '/'
}

TEST_CASE("excerpt cuts a long text and says how long it was", "[input_error]") {
  const std::string big(40u << 20, 'x');  // a 40 MB line
  const std::string e = excerpt(big);
  CHECK(e == "'" + std::string(kExcerptBytes, 'x') + "'... (41943040 bytes)");
  // A cut never splits a UTF-8 character.
  const std::string accents = std::string(59, 'a') + "\xc3\xa9" + "tail";
  CHECK(excerpt(accents) == "'" + std::string(59, 'a') + "'... (65 bytes)");
}

TEST_CASE("escape_controls keeps the whole text, escaped and unquoted", "[input_error]") {
  CHECK(escape_controls("engine \x1b[2Jgone") == "engine \\x1b[2Jgone");
  CHECK(escape_controls(std::string(100, 'n')) == std::string(100, 'n'));
}

TEST_CASE("a line is inert when it holds no control character, no line break and no tab",
          "[input]") {
  using dropcheck::find_unsafe_byte;
  using dropcheck::find_unsafe_in_line;
  CHECK(find_unsafe_in_line("w\xc3\xbcrfel 1/60") == std::string::npos);  // UTF-8 is fine
  CHECK(find_unsafe_in_line("a\tb") == 1);  // in a file, find_unsafe_byte allows a tab
  CHECK(find_unsafe_byte("a\tb") == std::string::npos);
  CHECK(find_unsafe_in_line("ab\n") == 2);
  CHECK(find_unsafe_in_line("x\x1b[2J") == 1);
  CHECK(find_unsafe_in_line("c1 \xc2\x9b") == 3);
  CHECK(find_unsafe_in_line("bad \xff utf8") == 4);
}
