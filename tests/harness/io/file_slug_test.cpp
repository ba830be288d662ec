#include "harness/io/file_slug.hpp"

#include <catch2/catch.hpp>
#include <string>

using namespace dropcheck;

TEST_CASE("file_slug keeps safe names and makes others safe", "[file_slug]") {
  CHECK(file_slug("free_fall") == "free_fall");
  CHECK(file_slug("../x") == "_.._x");
  CHECK(file_slug("/etc/passwd") == "_etc_passwd");
  CHECK(file_slug("") == "_");
}

TEST_CASE("file_slug shortens a long name to a stable, distinct slug", "[file_slug]") {
  const std::string a(255, 'a');
  std::string b = a;
  b.back() = 'b';  // differs only past the kept part
  const std::string sa = file_slug(a), sb = file_slug(b);
  CHECK(sa.size() == kMaxSlugBytes);
  CHECK(sa.substr(0, kMaxSlugBytes - 17) == std::string(kMaxSlugBytes - 17, 'a'));
  CHECK(sa[kMaxSlugBytes - 17] == '~');
  CHECK(sa != sb);
  CHECK(file_slug(a) == sa);  // the same every time (FNV-1a of the name, not a random suffix)
  // FNV-1a 64 of 255 'a's, computed independently (Python: h = 0xcbf29ce484222325;
  // for each byte h = ((h ^ byte) * 0x100000001b3) % 2**64).
  CHECK(sa.substr(kMaxSlugBytes - 16) == "7b04934eeef462a6");
  // A name of exactly kMaxSlugBytes is kept as it is.
  CHECK(file_slug(std::string(kMaxSlugBytes, 'c')) == std::string(kMaxSlugBytes, 'c'));
}
