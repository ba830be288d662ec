// Tests harness/process/stderr_capture.cpp: fd 2 taken into memory, counted, and given back.
#include "harness/process/stderr_capture.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>

using namespace dropcheck;

namespace {

// The inode behind fd 2: where stderr writes.
ino_t stderr_inode() {
  struct stat s {};
  REQUIRE(::fstat(STDERR_FILENO, &s) == 0);
  return s.st_ino;
}

}  // namespace

TEST_CASE("stderr is captured as counted lines and given back", "[process]") {
  const ino_t before = stderr_inode();
  StderrCapture capture;
  CHECK(stderr_inode() != before);
  for (int i = 0; i < 3; ++i) std::fputs("LCP internal error\n", stderr);
  std::fputs("\x1b[2J\n\nlast without a newline", stderr);
  const auto lines = capture.finish();
  CHECK(stderr_inode() == before);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == std::pair<std::string, std::int64_t>{"LCP internal error", 3});
  CHECK(lines[1].first == "\\x1b[2J");
  CHECK(lines[2].first == "last without a newline");
  CHECK(capture.finish().empty());  // once only
}
