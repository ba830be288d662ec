// Tests harness/process/child_process.cpp: lines both ways, bounded waits, exit descriptions, a
// dead reader that does not kill the writer (SIGPIPE), and no child left after the object goes.
#include "harness/process/child_process.hpp"

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <stdexcept>

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

bool gone(pid_t pid) {
  return ::kill(pid, 0) == -1 && errno == ESRCH;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TEST_CASE("A child echoes lines back in lockstep", "[child_process]") {
  ChildProcess cat({"cat"}, "");
  std::string line;
  for (const char* text : {"scene 1", "step 1 0 0 0", ""}) {
    REQUIRE(cat.write_line(text, 1.0) == IoStatus::ok);
    REQUIRE(cat.read_line(line, 1.0) == IoStatus::ok);
    CHECK(line == text);
  }
}

TEST_CASE("A read from a silent child times out, and the child is killed and reaped",
          "[child_process]") {
  pid_t pid = -1;
  const auto start = std::chrono::steady_clock::now();
  {
    ChildProcess sleeper({"sleep", "30"}, "");
    pid = sleeper.pid();
    std::string line;
    CHECK(sleeper.read_line(line, 0.2) == IoStatus::timeout);
  }
  CHECK(seconds_since(start) < 2.0);  // measured ~0.4 s: 0.2 s timeout + 0.2 s grace, then SIGKILL
  CHECK(gone(pid));
}

TEST_CASE("Exit statuses are described: crashed with the signal's name, or the exit code",
          "[child_process]") {
  ChildProcess segv({"sh", "-c", "kill -SEGV $$"}, "");
  std::string line;
  CHECK(segv.read_line(line, 2.0) == IoStatus::closed);
  CHECK(segv.exit_description() == "crashed: SIGSEGV");
  ChildProcess three({"sh", "-c", "exit 3"}, "");
  CHECK(three.read_line(line, 2.0) == IoStatus::closed);
  CHECK(three.exit_description() == "exited with status 3");
  CHECK(describe_wait_status(SIGABRT) == "crashed: SIGABRT");  // raw status of a signal death
}

TEST_CASE("Writing to a child that exited is an error value, not a SIGPIPE death",
          "[child_process]") {
  ChildProcess quitter({"true"}, "");
  std::string line;
  CHECK(quitter.read_line(line, 2.0) == IoStatus::closed);
  CHECK(quitter.exit_description() == "exited with status 0");
  IoStatus s = IoStatus::ok;
  for (int i = 0; i < 100 && s == IoStatus::ok; ++i)
    s = quitter.write_line(std::string(1000, 'x'), 1.0);
  CHECK(s == IoStatus::closed);
}

TEST_CASE("A child that does not read its input makes writes time out", "[child_process]") {
  ChildProcess sleeper({"sleep", "30"}, "");
  IoStatus s = IoStatus::ok;
  for (int i = 0; i < 1000 && s == IoStatus::ok; ++i)
    s = sleeper.write_line(std::string(4096, 'x'), 0.1);
  CHECK(s == IoStatus::timeout);  // the pipe (64 KiB) filled up
}

TEST_CASE("An endless line is cut off as too long", "[child_process]") {
  ChildProcess yes({"sh", "-c", "head -c 3000000 /dev/zero | tr '\\0' a; sleep 5"}, "");
  std::string line;
  CHECK(yes.read_line(line, 5.0) == IoStatus::too_long);
}

TEST_CASE("The child runs in the directory given, and a missing program is named",
          "[child_process]") {
  ChildProcess pwd({"pwd"}, "/");
  std::string line;
  REQUIRE(pwd.read_line(line, 2.0) == IoStatus::ok);
  CHECK(line == "/");
  try {
    ChildProcess missing({"/nonexistent/engine"}, "");
    FAIL("started a missing program");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(),
               Contains("cannot start '/nonexistent/engine'") && Contains("No such file"));
  }
}

TEST_CASE("Helpers a child started are killed with it (process group)", "[child_process]") {
  pid_t shell = -1;
  {
    ChildProcess sh({"sh", "-c", "sleep 30 & echo $!; wait"}, "");
    shell = sh.pid();
    std::string line;
    REQUIRE(sh.read_line(line, 2.0) == IoStatus::ok);
    const pid_t helper = static_cast<pid_t>(std::stol(line));
    sh.stop(0.1);
    CHECK(gone(shell));
    // The helper was SIGKILLed with the group; it is init's to reap, so wait until it is gone.
    const auto start = std::chrono::steady_clock::now();
    while (!gone(helper) && seconds_since(start) < 2.0) {
    }
    bool zombie_or_gone = gone(helper);
    if (!zombie_or_gone) {  // reaped by init a little later, or a zombie: not running either way
      char path[64];
      std::snprintf(path, sizeof path, "/proc/%d/stat", static_cast<int>(helper));
      FILE* f = std::fopen(path, "r");
      char state = 'Z';
      if (f) {
        (void)std::fscanf(f, "%*d %*s %c", &state);
        std::fclose(f);
      }
      zombie_or_gone = state == 'Z';
    }
    CHECK(zombie_or_gone);
  }
}
