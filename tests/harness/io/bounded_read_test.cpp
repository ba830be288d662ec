// Tests harness/io/bounded_read.cpp through load_scene: devices, FIFOs, directories and files
// over the 1 MiB limit are refused at once, before reading, with the limit named.
#include "harness/io/bounded_read.hpp"

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>

#include "../test_dirs.hpp"
#include "harness/core/input_error.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;

namespace {

// The message load_scene throws for `path`, and how long it took to throw it.
std::string read_refusal(const std::string& path, double& seconds) {
  const auto start = std::chrono::steady_clock::now();
  std::string what;
  try {
    load_scene(path);
  } catch (const InputError& e) {
    what = e.what();
  }
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return what;
}

}  // namespace

TEST_CASE("devices and FIFOs are refused at once, before a byte is read", "[loader][limits]") {
  ScratchDir dir("bounded-read");
  const std::string fifo = dir.file("endless.fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const std::string& path : {std::string("/dev/zero"), std::string("/dev/urandom"), fifo}) {
    INFO(path);
    double took = 0;
    CHECK_THAT(read_refusal(path, took), Contains("not a regular file (a device, FIFO or socket)"));
    CHECK(took < 1.0);  // measured < 1 ms; before, /dev/zero read until memory ran out
  }
  double took = 0;
  CHECK_THAT(read_refusal(dir.path.string(), took), Contains("it is a directory"));
  CHECK_THAT(read_refusal(dir.file("missing.toml"), took),
             Contains("cannot read the file: No such file"));
}

TEST_CASE("a scene file over 1 MiB is refused with its size and the limit", "[loader][limits]") {
  ScratchDir dir("bounded-size");
  const std::string big = dir.file("big.toml");
  std::ofstream(big) << "# " << std::string(kMaxSceneBytes, 'x') << "\n";
  double took = 0;
  CHECK_THAT(
      read_refusal(big, took),
      Contains("the file is 1048579 bytes, more than the limit of 1048576 bytes (1 MiB, for a "
               "scene)"));
  // At the limit it is read (and then refused only because it holds no scene).
  CHECK(read_regular_file(big, 2 << 20, "test").size() == 1048579);
}

TEST_CASE("LineReader streams lines, CRLF too, and numbers them", "[limits]") {
  ScratchDir d("line-reader");
  const std::string f = d.write("a.txt", "one\r\ntwo\n\nlast without a break");
  LineReader in(f, 1 << 20, 64, "a test file");
  std::vector<std::string> lines;
  for (std::string l; in.next(l);) lines.push_back(l);
  CHECK(lines == std::vector<std::string>{"one", "two", "", "last without a break"});
  CHECK(in.line_number() == 4);
}

TEST_CASE("LineReader refuses a line over its bound by file and line, never as the end of the file",
          "[limits]") {
  ScratchDir d("line-reader-long");
  // A 100 KiB line where at most 1 KiB is allowed: an error naming line 2, not two lines read.
  const std::string f = d.write("long.jsonl", "{}\n" + std::string(100 * 1024, 'x') + "\n{}\n");
  LineReader in(f, 1 << 20, 1024, "a shard file");
  std::string l;
  REQUIRE(in.next(l));
  CHECK_THROWS_WITH(in.next(l), Contains("long.jsonl:2") &&
                                    Contains("a line longer than 1024 bytes: not a shard file"));
  // The size bound is checked before a byte is read, and a name's control bytes are escaped.
  const std::string odd = d.write("odd\x1b[31m.jsonl", std::string(2048, '\n'));
  CHECK_THROWS_WITH(LineReader(odd, 1024, 64, "a shard file"),
                    Contains("odd\\x1b[31m.jsonl") && Contains("more than the limit of 1024"));
}
