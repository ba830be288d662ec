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
std::string refusal(const std::string& path, double& seconds) {
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
    CHECK_THAT(refusal(path, took), Contains("not a regular file (a device, FIFO or socket)"));
    CHECK(took < 1.0);  // measured < 1 ms; before, /dev/zero read until memory ran out
  }
  double took = 0;
  CHECK_THAT(refusal(dir.path.string(), took), Contains("it is a directory"));
  CHECK_THAT(refusal(dir.file("missing.toml"), took),
             Contains("cannot read the file: No such file"));
}

TEST_CASE("a scene file over 1 MiB is refused with its size and the limit", "[loader][limits]") {
  ScratchDir dir("bounded-size");
  const std::string big = dir.file("big.toml");
  std::ofstream(big) << "# " << std::string(kMaxSceneBytes, 'x') << "\n";
  double took = 0;
  CHECK_THAT(
      refusal(big, took),
      Contains("the file is 1048579 bytes, more than the limit of 1048576 bytes (1 MiB, for a "
               "scene)"));
  // At the limit it is read (and then refused only because it holds no scene).
  CHECK(read_regular_file(big, 2 << 20, "test").size() == 1048579);
}
