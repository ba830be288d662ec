#include "harness/process/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "harness/core/input_error.hpp"

extern char** environ;

namespace dropcheck {
namespace {

using Clock = std::chrono::steady_clock;

// A write to a pipe whose reader died raises SIGPIPE, which would kill dropcheck: ignore it once,
// process-wide, so that write() fails with EPIPE instead. The child gets the default back. And
// SIGCHLD at its default: a parent that started dropcheck with it ignored would pass that on, and
// the kernel would then reap every child itself, so no death could be named and no group killed.
void ignore_sigpipe() {
  static const bool done = [] {
    std::signal(SIGPIPE, SIG_IGN);
    std::signal(SIGCHLD, SIG_DFL);
    return true;
  }();
  (void)done;
}

// Milliseconds left until `deadline`, at least 0, for poll().
int ms_left(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return left.count() < 0 ? 0 : static_cast<int>(left.count());
}

Clock::time_point deadline_after(double seconds) {
  return Clock::now() + std::chrono::microseconds(static_cast<long long>(seconds * 1e6));
}

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// Starts the program; its stdin reads `in_read`, its stdout writes `out_write`.
pid_t spawn(const std::vector<std::string>& argv, const std::string& cwd, int in_read,
            int out_write) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in_read, STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out_write, STDOUT_FILENO);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setpgroup(&attr, 0);  // its own process group: stop() kills helpers it started
  sigset_t
      none;  // the caller holds SIGINT, SIGTERM and SIGHUP back (SignalsDeferred): not the child
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);

  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0)
    throw std::runtime_error("cannot start " + excerpt(argv[0]) +
                             (cwd.empty() ? "" : " in " + escape_controls(cwd)) + ": " +
                             std::strerror(rc));
  return pid;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& cwd) {
  if (argv.empty() || argv[0].empty()) throw std::runtime_error("empty command");
  ignore_sigpipe();
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]);
    ::close(in[1]);
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  }
  // Signals held back from the start of the child until it is registered (KillOnSignal): a Ctrl-C
  // between the two would leave the engine running.
  SignalsDeferred deferred;
  try {
    pid_ = spawn(argv, cwd, in[0], out[1]);
  } catch (...) {
    for (int fd : {in[0], in[1], out[0], out[1]}) ::close(fd);
    throw;
  }
  // Registered before anything else can fail: a signal to dropcheck from here on kills the group.
  kill_on_signal_.emplace(-pid_);  // no allocation: nothing can fail between spawn and this
  ::close(in[0]);
  ::close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  ::fcntl(to_child_, F_SETFL, ::fcntl(to_child_, F_GETFL) | O_NONBLOCK);
  ::fcntl(from_child_, F_SETFL, ::fcntl(from_child_, F_GETFL) | O_NONBLOCK);
}

ChildProcess::~ChildProcess() {
  stop();
}

IoStatus ChildProcess::write_line(const std::string& line, double timeout_s) {
  if (to_child_ < 0) return IoStatus::closed;
  const std::string data = line + "\n";
  const Clock::time_point deadline = deadline_after(timeout_s);
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(to_child_, data.data() + done, data.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN) return IoStatus::closed;  // EPIPE: the child is gone
    pollfd p{to_child_, POLLOUT, 0};
    const int r = ::poll(&p, 1, ms_left(deadline));
    if (r == 0) return IoStatus::timeout;
    if (r < 0 && errno != EINTR) return IoStatus::closed;
    if (p.revents & (POLLERR | POLLHUP)) return IoStatus::closed;
  }
  return IoStatus::ok;
}

IoStatus ChildProcess::read_line(std::string& line, double timeout_s) {
  const Clock::time_point deadline = deadline_after(timeout_s);
  for (;;) {
    if (const std::size_t nl = buffer_.find('\n'); nl != std::string::npos) {
      line.assign(buffer_, 0, nl);
      buffer_.erase(0, nl + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return IoStatus::ok;
    }
    if (buffer_.size() > kMaxLine) return IoStatus::too_long;
    if (from_child_ < 0) return IoStatus::closed;
    pollfd p{from_child_, POLLIN, 0};
    const int r = ::poll(&p, 1, ms_left(deadline));
    if (r == 0) return IoStatus::timeout;
    if (r < 0) {
      if (errno == EINTR) continue;
      return IoStatus::closed;
    }
    char chunk[65536];
    const ssize_t n = ::read(from_child_, chunk, sizeof chunk);
    if (n > 0) {
      buffer_.append(chunk, static_cast<std::size_t>(n));
    } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
      close_fd(from_child_);  // end of file: a partial last line is dropped as garbage-free EOF
      return IoStatus::closed;
    }
  }
}

// The child's process group is killed before the child is reaped, never after: while the child is
// an unreaped zombie its pid cannot be given to another process, so kill(-pid) reaches only the
// helpers it started (a shell wrapper's children, a forked server), never a stranger.
void ChildProcess::kill_group_and_reap() {
  ::kill(-pid_, SIGKILL);
  ::kill(pid_, SIGKILL);    // when it left its group (setpgid), the leader itself
  kill_on_signal_.reset();  // killed already: the signal handler must not reach the pid once freed
  for (;;) {
    if (::waitpid(pid_, &wait_status_, 0) == pid_) break;
    if (errno != EINTR) {  // reaped by someone else: how it ended is unknown
      wait_status_ = -1;
      break;
    }
  }
  reaped_ = true;
}

bool ChildProcess::reap(double wait_s) {
  if (reaped_ || pid_ < 0) return true;
  const Clock::time_point deadline = deadline_after(wait_s);
  for (;;) {
    // WNOWAIT: learn that it ended without reaping it yet (see kill_group_and_reap).
    siginfo_t info{};
    const int r = ::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT);
    if (r == 0 && info.si_pid == pid_) {
      kill_group_and_reap();
      return true;
    }
    if (r < 0 && errno != EINTR) {  // not our child any more: nothing to reap or describe
      reaped_ = true;
      wait_status_ = -1;
      kill_on_signal_.reset();
      return true;
    }
    if (Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void ChildProcess::stop(double grace_s) {
  close_fd(to_child_);
  if (pid_ < 0) return;
  if (!reap(grace_s)) kill_group_and_reap();
  close_fd(from_child_);
}

std::string ChildProcess::exit_description(double wait_s) {
  if (!reap(wait_s)) return "still running";
  return describe_wait_status(wait_status_);
}

std::string describe_wait_status(int status) {
  if (status == -1) return "ended, how unknown (not a child of this process)";
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const char* abbrev = sigabbrev_np(WTERMSIG(status));
    return std::string("crashed: ") +
           (abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(WTERMSIG(status)));
  }
  return "ended with wait status " + std::to_string(status);
}

}  // namespace dropcheck
