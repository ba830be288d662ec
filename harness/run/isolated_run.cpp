#include "harness/run/isolated_run.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <system_error>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/io/fd_write.hpp"
#include "harness/io/trajectory_wire.hpp"
#include "harness/process/signal_cleanup.hpp"
#include "harness/process/stderr_capture.hpp"
#include "harness/run/run_limits.hpp"

namespace dropcheck {
namespace {

using Clock = std::chrono::steady_clock;

Isolation g_default_isolation = Isolation::in_process;

// Exit codes of the child besides 0 (result sent) and death by a signal.
constexpr int kChildSendFailed = 3;   // the pipe broke while sending
constexpr int kChildOutOfMemory = 4;  // std::bad_alloc outside the run loop (while sending)
constexpr int kChildException = 5;    // any other exception outside the run loop

// What the child has done so far, in a page both processes share: written by the child, read by
// the parent after the child died or was killed.
struct Progress {
  std::atomic<std::int64_t> completed{0};  // steps completed
  std::atomic<int> phase{0};               // 0 loading the scene, 1 stepping, 2 sending the result
};
static_assert(std::atomic<std::int64_t>::is_always_lock_free &&
                  std::atomic<int>::is_always_lock_free,
              "lock-free atomics work across processes in shared memory");

// An anonymous shared mapping holding one Progress, unmapped at scope exit.
class SharedProgress {
 public:
  SharedProgress() {
    void* m = ::mmap(nullptr, sizeof(Progress), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS,
                     -1, 0);
    if (m == MAP_FAILED) throw std::bad_alloc();
    p_ = new (m) Progress;
  }
  ~SharedProgress() { ::munmap(p_, sizeof(Progress)); }
  SharedProgress(const SharedProgress&) = delete;
  SharedProgress& operator=(const SharedProgress&) = delete;
  Progress& operator*() const { return *p_; }

 private:
  Progress* p_ = nullptr;
};

// The engine as the child drives it, counting completed steps into the shared page.
class ProgressEngine final : public ForwardingEngine {
 public:
  ProgressEngine(Engine& inner, Progress& progress)
      : ForwardingEngine(inner), progress_(progress) {}
  void load(const Scene& scene, double h) override {
    inner_.load(scene, h);
    progress_.phase.store(1, std::memory_order_relaxed);
  }
  void step() override {
    inner_.step();
    progress_.completed.fetch_add(1, std::memory_order_relaxed);
  }

 private:
  Progress& progress_;
};

// The child: default signal actions (a test framework's or sanitizer's crash handlers must not run
// here: the parent reports the crash), stderr into the pipe, the ordinary loop, the result out.
[[noreturn]] void child_main(Engine& engine, const Scene& scene, double h,
                             const RunOptions& options, Progress& progress, int result_fd,
                             int err_fd) {
  // SIGINT and SIGHUP too: dropcheck's own handler (signal_cleanup.hpp) acts on the parent's
  // files and children, never from here.
  child_signals_to_defaults();  // the parent held SIGINT, SIGTERM, SIGHUP back around fork()
  ::dup2(err_fd, STDERR_FILENO);
  int code = 0;
  try {
    ProgressEngine counted(engine, progress);
    const Trajectory t = run_scene_in_process(counted, scene, h, options);
    progress.phase.store(2, std::memory_order_relaxed);
    const bool sent = write_trajectory(
        t, [result_fd](const void* d, std::size_t n) { return write_all(result_fd, d, n); });
    code = sent ? 0 : kChildSendFailed;
  } catch (const std::bad_alloc&) {
    code = kChildOutOfMemory;
  } catch (...) {
    code = kChildException;
  }
  std::fflush(nullptr);
  ::_exit(code);
}

// The parent's side of the two pipes: reads the result while reading the child's stderr into
// counted lines (so that neither pipe fills and blocks the child), until a deadline.
class ChildPipes {
 public:
  ChildPipes(int result_fd, int err_fd, Clock::time_point deadline)
      : result_(result_fd), err_(err_fd), deadline_(deadline) {}
  ~ChildPipes() {
    if (result_ >= 0) ::close(result_);
    if (err_ >= 0) ::close(err_);
  }
  ChildPipes(const ChildPipes&) = delete;
  ChildPipes& operator=(const ChildPipes&) = delete;

  // Exactly `bytes` bytes of the result; false at its end, on an error or at the deadline.
  bool read(void* data, std::size_t bytes) {
    char* p = static_cast<char*>(data);
    while (bytes > 0) {
      if (result_ < 0 || !wait()) return false;
      if (!result_ready_) continue;
      const ssize_t n = ::read(result_, p, bytes);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        close_fd(result_);
        return false;
      }
      p += n;
      bytes -= static_cast<std::size_t>(n);
    }
    return true;
  }

  // Waits for both pipes to close (the child exited), reading stderr; false at the deadline.
  bool drain() {
    char sink[4096];
    while (result_ >= 0 || err_ >= 0) {
      if (!wait()) return false;
      if (result_ready_) {
        const ssize_t n = ::read(result_, sink, sizeof sink);
        if (n == 0 || (n < 0 && errno != EINTR)) close_fd(result_);
      }
    }
    return true;
  }

  bool timed_out() const { return timed_out_; }

  // The last non-empty line the child wrote to stderr, cut to 300 bytes, controls escaped.
  std::string last_line() const {
    std::string s = tail_;
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    s = s.substr(s.find_last_of('\n') == std::string::npos ? 0 : s.find_last_of('\n') + 1);
    const bool cut = s.size() > 300;
    if (cut) s = s.substr(0, 300);
    return escape_controls(s) + (cut ? "..." : "");  // inert on a terminal: \xNN for controls
  }

 private:
  static constexpr std::size_t kTail = 4096;  // bytes of the child's stderr kept for last_line()

  void close_fd(int& fd) {
    ::close(fd);
    fd = -1;
  }

  // Polls both open pipes until one is ready or the deadline passes; stderr is read at once.
  bool wait() {
    for (;;) {
      const auto left =
          std::chrono::ceil<std::chrono::milliseconds>(deadline_ - Clock::now()).count();
      if (left <= 0) {
        timed_out_ = true;
        return false;
      }
      pollfd fds[2] = {{result_, POLLIN, 0}, {err_, POLLIN, 0}};
      const int r = ::poll(fds, 2, static_cast<int>(std::min<long long>(left, INT_MAX)));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) return false;
      if (r == 0) continue;  // re-check the deadline
      if (err_ >= 0 && fds[1].revents) pass_on_stderr();
      result_ready_ = result_ >= 0 && fds[0].revents;
      if (result_ready_ || result_ < 0) return true;
    }
  }

  // The child's stderr, read as it comes: kept as counted lines (Trajectory::messages), not
  // passed on, so that an engine's chatter does not flood the terminal.
  void pass_on_stderr() {
    char buf[4096];
    const ssize_t n = ::read(err_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) return;
    if (n <= 0) {
      close_fd(err_);
      lines_.add(partial_);
      partial_.clear();
      return;
    }
    tail_.append(buf, static_cast<std::size_t>(n));
    if (tail_.size() > kTail) tail_.erase(0, tail_.size() - kTail);
    for (ssize_t i = 0; i < n; ++i) {
      if (buf[i] != '\n') {
        if (partial_.size() < kLineBytes) partial_ += buf[i];
        continue;
      }
      lines_.add(partial_);
      partial_.clear();
    }
  }

 public:
  // What the child wrote to stderr, as counted lines, into `t` (a last line without its newline
  // too: a killed child's).
  void give_messages(Trajectory& t) {
    lines_.add(partial_);
    partial_.clear();
    t.messages = lines_.messages();
    t.other_lines = lines_.other_lines();
  }

 private:
  int result_, err_;
  Clock::time_point deadline_;
  bool timed_out_ = false;
  bool result_ready_ = false;
  std::string tail_;
  static constexpr std::size_t kLineBytes = 4096;  // a longer line is cut (then to 300 bytes)
  std::string partial_;                            // the line being read
  CountedLines lines_;
};

// Waits for `pid` to end, unregisters it from the signal handler while it is still a zombie (so
// that the handler never signals a pid freed by reaping), then reaps it; its wait status (or -1).
int reap(pid_t pid, std::optional<KillOnSignal>& kill_on_signal) {
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  kill_on_signal.reset();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return status;
}

// "SIGABRT" for SIGABRT.
std::string signal_name(int sig) {
  const char* abbrev = ::sigabbrev_np(sig);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(sig);
}

// Where the child was: "while loading the scene", "at step 12", "after the last step".
std::string where(const Progress& p, std::int64_t steps, std::int64_t& step) {
  const int phase = p.phase.load(std::memory_order_relaxed);
  step = p.completed.load(std::memory_order_relaxed) + (phase == 1 ? 1 : 0);
  if (phase == 0) return "while loading the scene";
  if (phase == 2 || step > steps) return "after the last step, while sending the result";
  return "at step " + std::to_string(step);
}

// The failed run of a child that died, exited with an error or was killed.
Trajectory child_failure(Trajectory t, int status, const ChildPipes& pipes, const Progress& p,
                         double limit) {
  const std::string at = where(p, t.steps, t.failed_step);
  const std::string line = pipes.last_line();
  const std::string said = line.empty() ? "" : " (" + line + ")";
  if (pipes.timed_out()) {
    t.status = RunStatus::timed_out;
    t.failure = "no result within the limit of " + sig(limit, 6) + " s; killed " + at;
  } else if (status != -1 && WIFSIGNALED(status)) {
    t.status = RunStatus::crashed;
    t.failure = signal_name(WTERMSIG(status)) + " " + at + said;
  } else if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == kChildOutOfMemory) {
    t.status = RunStatus::out_of_memory;
    t.failure = "allocation failed " + at;
  } else {
    t.status = RunStatus::crashed;
    t.failure = (status != -1 && WIFEXITED(status)
                     ? "engine process exited with code " + std::to_string(WEXITSTATUS(status))
                     : std::string("engine process ended without a result")) +
                " " + at + said;
  }
  return t;
}

// An engine in its own process, driven here: the run's wall-clock limit checked after each step.
class DeadlineEngine final : public ForwardingEngine {
 public:
  DeadlineEngine(Engine& inner, Clock::time_point deadline, double limit)
      : ForwardingEngine(inner), deadline_(deadline), limit_(limit) {}
  void step() override {
    inner_.step();
    if (Clock::now() > deadline_)
      throw RunTimeLimitExceeded("no result within the limit of " + sig(limit_, 6) + " s");
  }

 private:
  Clock::time_point deadline_;
  double limit_;
};

}  // namespace

Trajectory run_own_process(Engine& engine, const Scene& scene, double h,
                           const RunOptions& options) {
  const double limit =
      options.time_limit_seconds > 0 ? options.time_limit_seconds : kDefaultRunTimeLimitSeconds;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(std::min(limit, 1e9)));
  DeadlineEngine bounded(engine, deadline, limit);
  return run_scene_in_process(bounded, scene, h, options);
}

void set_default_isolation(Isolation isolation) {
  g_default_isolation = isolation == Isolation::process_default ? Isolation::in_process : isolation;
}

Isolation default_isolation() {
  return g_default_isolation;
}

bool runs_isolated(const RunOptions& options) {
  const Isolation i =
      options.isolation == Isolation::process_default ? g_default_isolation : options.isolation;
  return i == Isolation::child_process;
}

Trajectory run_isolated(Engine& engine, const Scene& scene, double h, const RunOptions& options) {
  const auto start = Clock::now();
  const double limit =
      options.time_limit_seconds > 0 ? options.time_limit_seconds : kDefaultRunTimeLimitSeconds;
  Trajectory failed = unstarted_trajectory(engine.info().name, scene, h);
  SharedProgress progress;
  int result[2], err[2];
  if (::pipe2(result, O_CLOEXEC) != 0)
    throw std::system_error(errno, std::generic_category(), "pipe");
  if (::pipe2(err, O_CLOEXEC) != 0) {
    ::close(result[0]);
    ::close(result[1]);
    throw std::system_error(errno, std::generic_category(), "pipe");
  }
  std::fflush(nullptr);  // nothing buffered may be written twice, by parent and child
  std::optional<KillOnSignal> kill_on_signal;  // dropcheck stopped: the child is killed first
  pid_t pid = -1;
  {
    SignalsDeferred deferred;  // no signal between fork() and the child's registration
    pid = ::fork();
    if (pid == 0) {
      ::close(result[0]);
      ::close(err[0]);
      child_main(engine, scene, h, options, *progress, result[1], err[1]);
    }
    if (pid > 0) kill_on_signal.emplace(pid);
  }
  ::close(result[1]);
  ::close(err[1]);
  if (pid < 0) {
    ::close(result[0]);
    ::close(err[0]);
    failed.status = RunStatus::engine_error;
    failed.failure = std::string("cannot start the engine process: ") + std::strerror(errno);
    return failed;
  }
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(std::min(limit, 1e9)));
  ChildPipes pipes(result[0], err[0], deadline);
  Trajectory t;
  const std::int64_t max_samples = recorded_samples(failed.steps, options.record_every);
  const bool got = read_trajectory(t, scene.bodies.size(), max_samples,
                                   [&pipes](void* d, std::size_t n) { return pipes.read(d, n); });
  if (!pipes.timed_out()) pipes.drain();
  if (pipes.timed_out()) ::kill(pid, SIGKILL);
  const int status = reap(pid, kill_on_signal);
  const bool clean = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (got && clean && !pipes.timed_out()) {
    pipes.give_messages(t);
    return t;
  }
  failed.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  pipes.give_messages(failed);
  return child_failure(std::move(failed), status, pipes, *progress, limit);
}

}  // namespace dropcheck
