#include "harness/plan/worker.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <memory>
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

bool put_index(int fd, char tag, std::uint64_t i) {
  return write_all(fd, &tag, 1) && write_all(fd, &i, sizeof i);
}

// The queue every worker pulls from: the next position in `cells`, in memory shared by the forked
// workers, so that a worker that finishes early takes the next cell instead of idling while a
// slower one works through a fixed share.
struct SharedQueue {
  std::atomic<std::uint64_t> next{0};
};

// A worker: crash signals to their defaults (the parent reads a death, not a handler's report),
// killed with its parent; it takes cell after cell from the queue and runs each in this process,
// sending 'S' and the cell's position before it runs, 'R', the position, the status and the record
// after it.
[[noreturn]] void worker_main(const Plan& plan, const std::vector<std::size_t>& cells,
                              SharedQueue& queue, int fd) {
  child_signals_to_defaults();
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  int code = 0;
  try {
    for (;;) {
      const std::uint64_t i = queue.next.fetch_add(1);
      if (i >= cells.size()) break;
      if (!put_index(fd, 'S', i)) {
        code = 3;
        break;
      }
      // The run limit of a cell run alone, checked after every step: a slow cell times out here
      // as it would there (its record names the limit, not the step); a step that never returns
      // is the parent's watchdog's.
      const CellRecord r =
          run_cell(plan, plan.cell(cells[i]), Isolation::in_process, kDefaultRunTimeLimitSeconds);
      if (!put_index(fd, 'R', i) || !put_text(fd, r.status) || !put_text(fd, r.line)) {
        code = 3;
        break;
      }
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

using Clock = std::chrono::steady_clock;
constexpr std::size_t kNoCell = static_cast<std::size_t>(-1);

// One worker as the parent sees it: its pipe, the cell it announced and has not answered, and
// when it last said anything.
struct WorkerSlot {
  pid_t pid = -1;
  int fd = -1;
  std::unique_ptr<KillOnSignal> kill_on_signal;  // (not movable itself)
  std::size_t current = kNoCell;
  Clock::time_point heard;
};

WorkerSlot start_worker(const Plan& plan, const std::vector<std::size_t>& cells,
                        SharedQueue& queue) {
  int pipe[2];
  if (::pipe2(pipe, O_CLOEXEC) != 0)
    throw std::system_error(errno, std::generic_category(), "pipe");
  std::fflush(nullptr);
  WorkerSlot w;
  {
    SignalsDeferred deferred;
    w.pid = ::fork();
    if (w.pid == 0) {
      ::close(pipe[0]);
      worker_main(plan, cells, queue, pipe[1]);
    }
    if (w.pid > 0) w.kill_on_signal = std::make_unique<KillOnSignal>(w.pid);
  }
  ::close(pipe[1]);
  if (w.pid < 0) {
    ::close(pipe[0]);
    throw std::system_error(errno, std::generic_category(), "fork");
  }
  w.fd = pipe[0];
  w.heard = Clock::now();
  return w;
}

// Ends a worker (done, dead or silent past the limit): killed, reaped, its pipe closed.
void stop_worker(WorkerSlot& w) {
  ::close(w.fd);
  ::kill(w.pid, SIGKILL);
  int wstatus = 0;
  while (::waitpid(w.pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  w.kill_on_signal.reset();
  w.fd = -1;
  w.pid = -1;
}

// Reads one frame from a worker whose pipe is readable; false when it ended or sent garbage.
bool read_frame(WorkerSlot& w, std::vector<CellRecord>& out, std::size_t cells,
                const std::function<void(std::size_t, const CellRecord&)>& done, int wait_ms) {
  char tag = 0;
  std::uint64_t i = 0;
  if (!read_exact(w.fd, &tag, 1, wait_ms) || !read_exact(w.fd, &i, sizeof i, wait_ms) || i >= cells)
    return false;
  w.heard = Clock::now();
  if (tag == 'S') {
    w.current = static_cast<std::size_t>(i);
    return true;
  }
  if (tag != 'R' || i != w.current) return false;
  std::optional<std::string> status = get_text(w.fd, wait_ms);
  std::optional<std::string> line = status ? get_text(w.fd, wait_ms) : std::nullopt;
  if (!line) return false;
  out[i] = {std::move(*status), std::move(*line)};
  w.current = kNoCell;
  if (done) done(static_cast<std::size_t>(i), out[i]);
  return true;
}

}  // namespace

int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

std::vector<CellRecord> run_cells_in_worker(
    const Plan& plan, const std::vector<std::size_t>& cells,
    const std::function<void(std::size_t, const CellRecord&)>& done,
    std::chrono::milliseconds silence, WorkerStats* stats, int jobs) {
  const int wait_ms = static_cast<int>(std::clamp<std::int64_t>(silence.count(), 1, INT32_MAX));
  WorkerStats local;
  WorkerStats& count = stats ? *stats : local;
  std::vector<CellRecord> out(cells.size());
  if (cells.empty()) return out;
  // The queue in memory the forked workers share (an anonymous shared mapping).
  void* shared = ::mmap(nullptr, sizeof(SharedQueue), PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) throw std::system_error(errno, std::generic_category(), "mmap");
  SharedQueue* queue = new (shared) SharedQueue;
  const auto left = [&] { return queue->next.load() < cells.size(); };
  std::vector<WorkerSlot> slots;
  const std::size_t wanted =
      std::min<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)), cells.size());
  try {
    for (std::size_t k = 0; k < wanted; ++k) {
      slots.push_back(start_worker(plan, cells, *queue));
      ++count.workers;
    }
    while (!slots.empty()) {
      std::vector<pollfd> fds;
      for (const WorkerSlot& w : slots) fds.push_back({w.fd, POLLIN, 0});
      // Wake at the earliest silence limit among the workers.
      Clock::time_point deadline = Clock::time_point::max();
      for (const WorkerSlot& w : slots) deadline = std::min(deadline, w.heard + silence);
      const auto until =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      const int ready =
          ::poll(fds.data(), fds.size(),
                 static_cast<int>(std::clamp<std::int64_t>(until.count(), 0, wait_ms)));
      if (ready < 0 && errno != EINTR)
        throw std::system_error(errno, std::generic_category(), "poll");
      for (std::size_t k = slots.size(); k-- > 0;) {
        WorkerSlot& w = slots[k];
        bool ended = false;
        if (ready > 0 && fds[k].revents != 0)
          ended = !read_frame(w, out, cells.size(), done, wait_ms);
        else if (Clock::now() - w.heard >= silence)
          ended = true;
        if (!ended) continue;
        const std::size_t lost = w.current;
        stop_worker(w);
        slots.erase(slots.begin() + static_cast<std::ptrdiff_t>(k));
        // A worker that ended while cells are queued died (one that finishes found the queue
        // empty): a new one takes its place.
        if (left()) {
          slots.push_back(start_worker(plan, cells, *queue));
          ++count.workers;
        }
        if (lost == kNoCell) continue;  // it left no announced cell unanswered
        ++count.rerun_alone;
        // The worker died in that cell or outlasted its limit there: the cell the per-cell way.
        // That may take minutes in which no worker is heard: each is given its silence afresh,
        // and the pipes are polled again before any is judged.
        out[lost] = run_cell(plan, plan.cell(cells[lost]), Isolation::child_process);
        if (done) done(lost, out[lost]);
        for (WorkerSlot& other : slots) other.heard = Clock::now();
        break;
      }
    }
  } catch (...) {
    for (WorkerSlot& w : slots) stop_worker(w);
    ::munmap(shared, sizeof(SharedQueue));
    throw;
  }
  ::munmap(shared, sizeof(SharedQueue));
  // A worker that died between taking a cell and announcing it left that cell unanswered.
  for (std::size_t k = 0; k < cells.size(); ++k)
    if (out[k].line.empty()) {
      ++count.rerun_alone;
      out[k] = run_cell(plan, plan.cell(cells[k]), Isolation::child_process);
      if (done) done(k, out[k]);
    }
  return out;
}

}  // namespace dropcheck
