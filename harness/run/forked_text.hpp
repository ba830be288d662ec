// A piece of work run in a forked child while this process goes on with another: the report's
// stability section beside its scenes, on the second core. The child computes a string and sends
// it back over a pipe; the parent collects it when it needs it. Forked while this process has one
// thread (dropcheck never starts another), so the child may do anything the parent could,
// including forking isolated runs of its own; both share the terminal's stderr for progress.
#pragma once

#include <sys/types.h>

#include <functional>
#include <optional>
#include <string>

#include "harness/process/signal_cleanup.hpp"

namespace dropcheck {

class ForkedText {
 public:
  // Starts `work` in a child process; where fork fails, runs it here and now instead, so the
  // caller gets the same text either way.
  explicit ForkedText(const std::function<std::string()>& work);
  // Kills a child whose text was never collected, with every process it started (it leads a
  // process group of its own), and reaps it.
  ~ForkedText();
  ForkedText(const ForkedText&) = delete;
  ForkedText& operator=(const ForkedText&) = delete;

  // Waits for the child and returns its text. Throws std::runtime_error when the work threw (with
  // its message) or the child died; the text once collected is returned again.
  std::string get();

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::optional<KillOnSignal> kill_on_signal_;
  std::optional<std::string> text_;
};

}  // namespace dropcheck
