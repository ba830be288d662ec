// Tests harness/io/atomic_file.cpp: a file is written whole or not at all, and a failure names
// the path.
#include "harness/io/atomic_file.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../test_dirs.hpp"
#include "harness/core/input_error.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it)
    ++n;
  return n;
}

// The InputError message of writing `content` to `path`, or "(written)".
std::string write_error(const std::string& path, const std::string& content) {
  try {
    dropcheck::write_file_atomic(path, content);
  } catch (const dropcheck::InputError& e) {
    return e.what();
  }
  return "(written)";
}

}  // namespace

TEST_CASE("write_file_atomic writes the whole content, bytes included, and no temporary remains",
          "[atomic_file]") {
  ScratchDir dir("whole");
  std::string content(1 << 20, 'x');
  content[10] = '\0';
  content[20] = '\n';
  dropcheck::write_file_atomic(dir.file("out.csv"), content);
  CHECK(slurp(dir.file("out.csv")) == content);
  CHECK_FALSE(fs::exists(dir.file("out.csv.tmp")));
  CHECK(entries(dir.path) == 1);
}

TEST_CASE("write_file_atomic replaces an existing file and creates missing parent directories",
          "[atomic_file]") {
  ScratchDir dir("replace");
  dropcheck::write_file_atomic(dir.file("a/b/out.json"), "first, and longer than the second");
  dropcheck::write_file_atomic(dir.file("a/b/out.json"), "second");
  CHECK(slurp(dir.file("a/b/out.json")) == "second");
  CHECK(entries(dir.path) == 3);  // a, a/b, a/b/out.json
}

TEST_CASE("a path under a regular file throws InputError naming the path and leaves nothing",
          "[atomic_file]") {
  ScratchDir dir("notdir");
  dropcheck::write_file_atomic(dir.file("file"), "I am not a directory");
  const std::string target = dir.file("file/out.csv");
  CHECK_THAT(write_error(target, "data"),
             Contains(target) && Contains("cannot write") && Contains("Not a directory"));
  CHECK(entries(dir.path) == 1);  // only the regular file: no out.csv, no .tmp
  CHECK(slurp(dir.file("file")) == "I am not a directory");
}

TEST_CASE("a target that is a directory throws InputError with the reason and leaves no temporary",
          "[atomic_file]") {
  ScratchDir dir("isdir");
  fs::create_directories(dir.path / "out.csv" / "inside");
  const std::string target = dir.file("out.csv");
  const std::string msg = write_error(target, "data");
  CHECK_THAT(msg, Contains(target) && Contains("cannot replace the file") && Contains("directory"));
  CHECK_FALSE(fs::exists(target + ".tmp"));
  CHECK(fs::is_directory(dir.path / "out.csv" / "inside"));  // the directory is untouched
}
