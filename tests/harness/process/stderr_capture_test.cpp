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
  const std::vector<Trajectory::Message> lines = capture.finish().messages();
  CHECK(stderr_inode() == before);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].text == "LCP internal error");
  CHECK(lines[0].count == 3);
  CHECK(lines[1].text == "\\x1b[2J");
  CHECK(lines[2].text == "last without a newline");
  CHECK(capture.finish().messages().empty());  // once only
}
