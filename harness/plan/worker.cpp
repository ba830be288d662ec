#include "harness/plan/worker.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <system_error>

#include "harness/io/fd_write.hpp"
#include "harness/process/signal_cleanup.hpp"
#include "harness/run/isolated_run.hpp"

namespace dropcheck {
namespace {

static_assert(kWorkerSilenceLimit.count() >= (kDefaultRunTimeLimitSeconds + 60.0) * 1000.0,
              "a worker must be given at least as long as a cell run alone");

bool put_text(int fd, const std::string& s) {
  const std::uint64_t n = s.size();
  return write_all(fd, &n, sizeof n) && write_all(fd, s.data(), s.size());
}

// The worker: crash signals to their defaults (the parent reads a death, not a handler's report),
// killed with its parent, each cell run in this process; one frame per record.
[[noreturn]] void worker_main(const Plan& plan, const std::vector<std::size_t>& cells,
                              std::size_t from, int fd) {
  child_signals_to_defaults();
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  int code = 0;
  try {
    for (std::size_t i = from; i < cells.size() && code == 0; ++i) {
      // The run limit of a cell run alone, checked after every step: a slow cell times out here
      // as it would there (its record names the limit, not the step); a step that never returns
      // is the parent's watchdog's.
      const CellRecord r =
          run_cell(plan, plan.cell(cells[i]), Isolation::in_process, kDefaultRunTimeLimitSeconds);
      if (!put_text(fd, r.status) || !put_text(fd, r.line)) code = 3;
    }
  } catch (...) {
    code = 4;
  }
  std::fflush(nullptr);
  ::_exit(code);
}

// Reads exactly n bytes, waiting at most `wait_ms` for each chunk; false at the end of the pipe,
// on an error or on the time limit.
bool read_exact(int fd, void* data, std::size_t n, int wait_ms) {
  char* p = static_cast<char*>(data);
  while (n > 0) {
    pollfd pfd{fd, POLLIN, 0};
    const int ready = ::poll(&pfd, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return false;
    const ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    n -= static_cast<std::size_t>(r);
  }
  return true;
}

std::optional<std::string> get_text(int fd, int wait_ms) {
  std::uint64_t n = 0;
  if (!read_exact(fd, &n, sizeof n, wait_ms) || n > (std::uint64_t{1} << 30)) return std::nullopt;
  std::string s(n, '\0');
  if (!read_exact(fd, s.data(), s.size(), wait_ms)) return std::nullopt;
  return s;
}

// Runs cells[from..] in one worker; returns how many records it sent before it ended.
std::size_t one_worker(const Plan& plan, const std::vector<std::size_t>& cells, std::size_t from,
                       std::vector<CellRecord>& out,
                       const std::function<void(std::size_t, const CellRecord&)>& done,
                       int wait_ms) {
  int pipe[2];
  if (::pipe2(pipe, O_CLOEXEC) != 0)
    throw std::system_error(errno, std::generic_category(), "pipe");
  std::fflush(nullptr);
  std::optional<KillOnSignal> kill_on_signal;
  pid_t pid = -1;
  {
    SignalsDeferred deferred;
    pid = ::fork();
    if (pid == 0) {
      ::close(pipe[0]);
      worker_main(plan, cells, from, pipe[1]);
    }
    if (pid > 0) kill_on_signal.emplace(pid);
  }
  ::close(pipe[1]);
  if (pid < 0) {
    ::close(pipe[0]);
    throw std::system_error(errno, std::generic_category(), "fork");
  }
  std::size_t sent = 0;
  for (std::size_t i = from; i < cells.size(); ++i) {
    std::optional<std::string> status = get_text(pipe[0], wait_ms);
    std::optional<std::string> line = status ? get_text(pipe[0], wait_ms) : std::nullopt;
    if (!line) break;
    out[i] = {std::move(*status), std::move(*line)};
    if (done) done(i, out[i]);
    ++sent;
  }
  ::close(pipe[0]);
  ::kill(pid, SIGKILL);  // ended, or silent past the limit: either way it goes
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  return sent;
}

}  // namespace

std::vector<CellRecord> run_cells_in_worker(
    const Plan& plan, const std::vector<std::size_t>& cells,
    const std::function<void(std::size_t, const CellRecord&)>& done,
    std::chrono::milliseconds silence, WorkerStats* stats) {
  const int wait_ms = static_cast<int>(std::clamp<std::int64_t>(silence.count(), 1, INT32_MAX));
  WorkerStats local;
  WorkerStats& count = stats ? *stats : local;
  std::vector<CellRecord> out(cells.size());
  std::size_t next = 0;
  while (next < cells.size()) {
    ++count.workers;
    next += one_worker(plan, cells, next, out, done, wait_ms);
    if (next >= cells.size()) break;
    ++count.rerun_alone;
    // The worker died in cells[next] or outlasted its limit there: that cell the per-cell way.
    out[next] = run_cell(plan, plan.cell(cells[next]), Isolation::child_process);
    if (done) done(next, out[next]);
    ++next;
  }
  return out;
}

}  // namespace dropcheck
