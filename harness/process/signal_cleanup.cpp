#include "harness/process/signal_cleanup.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace dropcheck {
namespace {

// The table the handler reads. A slot's path is written before its state turns to "file" or
// "folder" (a sequentially consistent store), so the handler never sees half a path.
constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;
enum : int { kFree = 0, kFile = 1, kFolder = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathMax];
};
Slot g_slots[kSlots];

// Child processes to kill first (0: a free slot; -pid: the process group pid leads). One per
// external engine alive at once, one per isolated run, one gnuplot.
// Children and process groups: a sweep's workers (up to --jobs 1024), each with a rerun's isolated
// child at most, and the rest of dropcheck's helpers.
constexpr int kChildSlots = 2048;
std::atomic<pid_t> g_children[kChildSlots];

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

// Removes a folder's entries (one level: staging folders are flat) and the folder. Only
// async-signal-safe calls: open, getdents64 (a plain system call), unlinkat, close, rmdir.
void remove_folder(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
  if (fd >= 0) {
    alignas(8) char buf[4096];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
      if (n <= 0) break;
      for (long off = 0; off < n;) {
        // struct linux_dirent64: u64 ino, s64 off, u16 reclen, u8 type, char name[].
        unsigned short reclen;
        std::memcpy(&reclen, buf + off + 16, sizeof reclen);
        const char* name = buf + off + 19;
        if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) ::unlinkat(fd, name, 0);
        off += reclen;
      }
    }
    ::close(fd);
  }
  ::rmdir(path);
}

void on_signal(int sig) {
  for (std::atomic<pid_t>& child : g_children) {  // kill and waitpid are async-signal-safe
    const pid_t pid = child.load();
    if (pid == 0) continue;
    const pid_t leader = pid < 0 ? -pid : pid;
    const bool sent = ::kill(pid, SIGKILL) == 0;  // a negative pid: the whole group
    if ((::kill(leader, SIGKILL) == 0 || sent)) ::waitpid(leader, nullptr, 0);
  }
  for (Slot& s : g_slots) {
    const int state = s.state.load();
    if (state == kFile) ::unlink(s.path);
    if (state == kFolder) remove_folder(s.path);
  }
  // Then what was there before (by default: die of the same signal, as the shell expects). The
  // signal is blocked while this handler runs, so the raised one is delivered right after it.
  for (int i = 0; i < 3; ++i)
    if (kSignals[i] == sig) ::sigaction(sig, &g_previous[i], nullptr);
  ::raise(sig);
}

// Installs on_signal where it is not the handler now, keeping the one it replaces to chain to. Run
// at every registration: a test framework may have put its own handler back meanwhile.
void install() {
  for (int i = 0; i < 3; ++i) {
    struct sigaction current {};
    ::sigaction(kSignals[i], nullptr, &current);
    if (current.sa_handler == SIG_IGN || current.sa_handler == on_signal)
      continue;  // nohup: stay ignored
    struct sigaction now {};
    now.sa_handler = on_signal;
    sigemptyset(&now.sa_mask);
    for (int s : kSignals) sigaddset(&now.sa_mask, s);  // one handler at a time
    g_previous[i] = current;
    ::sigaction(kSignals[i], &now, nullptr);
  }
}

}  // namespace

CleanupOnSignal::CleanupOnSignal(const std::string& path, bool folder) {
  if (path.size() + 1 > kPathMax || path.find('\0') != std::string::npos) return;
  install();
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    // Claim with an intermediate value (-1) so that the handler skips the slot while we copy.
    if (!g_slots[i].state.compare_exchange_strong(expected, -1)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].state.store(folder ? kFolder : kFile);
    slot_ = i;
    return;
  }
}

CleanupOnSignal::~CleanupOnSignal() {
  release();
}

void CleanupOnSignal::release() {
  if (slot_ >= 0) g_slots[slot_].state.store(kFree);
  slot_ = -1;
}

KillOnSignal::KillOnSignal(pid_t pid) {
  install();
  for (int i = 0; i < kChildSlots; ++i) {
    pid_t expected = 0;
    if (g_children[i].compare_exchange_strong(expected, pid)) {
      slot_ = i;
      return;
    }
  }
}

KillOnSignal::~KillOnSignal() {
  if (slot_ >= 0) g_children[slot_].store(0);
}

SignalsDeferred::SignalsDeferred() {
  sigset_t block;
  sigemptyset(&block);
  for (int sig : kSignals) sigaddset(&block, sig);
  ::sigprocmask(SIG_BLOCK, &block, &previous_);
}

SignalsDeferred::~SignalsDeferred() {
  ::sigprocmask(SIG_SETMASK, &previous_, nullptr);
}

void child_signals_to_defaults() {
  for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGPIPE, SIGTERM, SIGINT, SIGHUP})
    std::signal(sig, SIG_DFL);
  sigset_t deferred;
  sigemptyset(&deferred);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&deferred, sig);
  ::sigprocmask(SIG_UNBLOCK, &deferred, nullptr);
}

}  // namespace dropcheck
