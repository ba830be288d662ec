#include "harness/run/forked_text.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>

#include "harness/io/fd_write.hpp"

namespace dropcheck {
namespace {

// The child's message: one status byte ('+' the text follows, '!' an error message follows).
[[noreturn]] void forked_child_main(const std::function<std::string()>& work, int fd) {
  // A process group of its own: stopping it stops the isolated runs and engines it started too.
  ::setpgid(0, 0);
  child_signals_to_defaults();
  std::string message;
  char status = '+';
  try {
    message = work();
  } catch (const std::exception& e) {
    status = '!';
    message = e.what();
  } catch (...) {
    status = '!';
    message = "an unknown exception";
  }
  const bool sent = write_all(fd, &status, 1) && write_all(fd, message.data(), message.size());
  std::fflush(nullptr);
  ::_exit(sent ? 0 : 1);
}

}  // namespace

ForkedText::ForkedText(const std::function<std::string()>& work) {
  int p[2];
  if (::pipe2(p, O_CLOEXEC) != 0) {  // an engine the child execs must not hold the pipe open
    text_ = work();
    return;
  }
  std::fflush(nullptr);  // nothing buffered is written twice
  {
    SignalsDeferred deferred;  // no signal between fork() and the child's registration
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(p[0]);
      forked_child_main(work, p[1]);
    }
    if (pid_ > 0) {
      ::setpgid(pid_, pid_);  // (also in the child: whichever runs first)
      kill_on_signal_.emplace(-pid_);
    }
  }
  ::close(p[1]);
  if (pid_ < 0) {
    ::close(p[0]);
    text_ = work();
    return;
  }
  fd_ = p[0];
}

ForkedText::~ForkedText() {
  if (fd_ >= 0) ::close(fd_);
  if (pid_ > 0) {
    ::kill(-pid_, SIGKILL);  // the child's whole group
    while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
}

std::string ForkedText::get() {
  if (text_) return *text_;
  std::string all;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0) all.append(buf, static_cast<std::size_t>(n));
    if (n == 0 || (n < 0 && errno != EINTR)) break;
  }
  ::close(fd_);
  fd_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  kill_on_signal_.reset();
  const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!clean || all.empty())
    throw std::runtime_error(WIFSIGNALED(status) ? "the child process died of signal " +
                                                       std::to_string(WTERMSIG(status))
                                                 : "the child process ended without its text");
  if (all[0] == '!') throw std::runtime_error(all.substr(1));
  text_ = all.substr(1);
  return *text_;
}

}  // namespace dropcheck
