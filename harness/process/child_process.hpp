// ChildProcess: a program started with its stdin and stdout on pipes, for talking to it line by
// line in lockstep (adapters/exec.cpp). Every wait is bounded, a dead child never kills the caller
// (SIGPIPE is ignored; a broken pipe is an error value), and neither the child nor any helper it
// started outlives the object: the child leads a process group of its own, and that whole group
// is killed when the child is reaped (it ended, failed or was stopped) and when dropcheck is
// stopped by SIGINT, SIGTERM or SIGHUP (KillOnSignal).
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

#include "harness/process/signal_cleanup.hpp"

namespace dropcheck {

// What a bounded read or write came to.
enum class IoStatus {
  ok,        // the line was read or written in full
  timeout,   // the child did not answer (or read) within the time allowed
  closed,    // the child closed its end (it exited, crashed, or closed stdout/stdin)
  too_long,  // a line longer than ChildProcess::kMaxLine arrived (garbage)
};

class ChildProcess {
 public:
  // Longest line read_line accepts (bytes, newline excluded): a bound on garbage.
  static constexpr std::size_t kMaxLine = 1 << 20;

  // Starts argv[0] (searched in PATH when it has no '/') with `argv` in directory `cwd` ("" =
  // ours). stderr is inherited. Throws std::runtime_error naming the program when it cannot be
  // started.
  ChildProcess(const std::vector<std::string>& argv, const std::string& cwd);
  // Closes the pipes, gives the child 0.2 s to exit, then kills it; always reaps it.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Writes `line` plus '\n', waiting at most `timeout_s` for the pipe to take it.
  IoStatus write_line(const std::string& line, double timeout_s);
  // Reads the next line (without '\n'), waiting at most `timeout_s` in total.
  IoStatus read_line(std::string& line, double timeout_s);

  // Closes the child's stdin (it sees end of input), waits up to `grace_s` for it to exit, then
  // SIGKILLs it; kills its process group and reaps it either way. Idempotent.
  void stop(double grace_s = 0.2);
  // How the child ended, once it has ("exited with status 3", "crashed: SIGSEGV"); waits up to
  // `wait_s` for it to end, "still running" if it has not.
  std::string exit_description(double wait_s = 0.5);

  pid_t pid() const { return pid_; }  // the child's process id (for tests)

 private:
  bool reap(double wait_s);    // a bounded wait for the child to end; true once it is reaped
  void kill_group_and_reap();  // SIGKILL to the group and the child, then waitpid

  pid_t pid_ = -1;
  int to_child_ = -1;    // our end of the child's stdin
  int from_child_ = -1;  // our end of the child's stdout
  bool reaped_ = false;
  int wait_status_ = 0;  // from waitpid, valid when reaped_ (-1: not our child, status unknown)
  std::optional<KillOnSignal> kill_on_signal_;  // the group, killed if dropcheck is stopped
  std::string buffer_;                          // bytes read past the last line returned
};

// "exited with status 3", "crashed: SIGSEGV" (signal name from the C library), from a waitpid
// status.
std::string describe_wait_status(int status);

}  // namespace dropcheck
