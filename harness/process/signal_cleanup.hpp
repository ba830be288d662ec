// Temporary files and staging folders are removed when dropcheck is interrupted (SIGINT, SIGTERM,
// SIGHUP), after the child processes writing into them are killed: a killed run leaves the
// previous output intact and nothing of its own behind.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <string>

namespace dropcheck {

// A path removed by the signal handler while registered: a file (unlink) or a folder (its entries,
// one level deep, then the folder). Unregisters itself at scope exit. Not copyable.
class CleanupOnSignal {
 public:
  // Registers `path` (installing the handlers on first use); a path too long for the table's slot
  // or a full table is not registered and the object is inert (the run still works).
  CleanupOnSignal(const std::string& path, bool folder);
  ~CleanupOnSignal();
  CleanupOnSignal(const CleanupOnSignal&) = delete;
  CleanupOnSignal& operator=(const CleanupOnSignal&) = delete;

  // Stops removing the path on a signal (it became the output, or was removed).
  void release();

 private:
  int slot_ = -1;
};

// A child process (gnuplot, an isolated run) or a whole process group (an external engine and the
// helpers it started) killed and reaped by the signal handler, before the paths are removed, while
// registered: it can then write nothing more into a folder being removed, and does not outlive
// dropcheck. Unregisters itself at scope exit. Not copyable.
class KillOnSignal {
 public:
  // Registers `pid`, or with -pid the process group pid leads (installing the handlers on first
  // use); inert when the table is full.
  explicit KillOnSignal(pid_t pid);
  ~KillOnSignal();
  KillOnSignal(const KillOnSignal&) = delete;
  KillOnSignal& operator=(const KillOnSignal&) = delete;

 private:
  int slot_ = -1;
};

// Holds SIGINT, SIGTERM and SIGHUP back for its lifetime (delivered when it ends): makes "create a
// temporary path and register it" one step, so a signal between the two leaves nothing behind.
class SignalsDeferred {
 public:
  SignalsDeferred();
  ~SignalsDeferred();
  SignalsDeferred(const SignalsDeferred&) = delete;
  SignalsDeferred& operator=(const SignalsDeferred&) = delete;

 private:
  sigset_t previous_;
};

// In a child forked under SignalsDeferred (an isolated run, a shard's worker): the crash and stop
// signals back to their defaults, so the parent reads a death rather than a handler's report, and
// dropcheck's own handler never acts on the parent's files from here; then the deferred signals
// unblocked.
void child_signals_to_defaults();

}  // namespace dropcheck
