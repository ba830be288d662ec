// An engine's stderr as counted lines (Trajectory::messages): kept from the terminal, each distinct
// line once with its count. CountedLines counts them, for an isolated run's pipe
// (harness/run/isolated_run.cpp) and for StderrCapture, which takes this process's fd 2 into memory
// while in-process engines are timed (harness/study/evaluate.cpp time_evaluations).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

class CountedLines {
 public:
  // One line (its newline stripped): trailing '\r' and spaces dropped, an empty one ignored, cut
  // to 300 bytes ("..." added), controls escaped; counted with its equals, the first
  // Trajectory::kKeptMessages distinct ones kept, the others counted in other_lines().
  void add(std::string_view raw);
  // Every line of `text`, the last one without its newline too.
  void add_text(std::string_view text);
  const std::vector<Trajectory::Message>& messages() const { return messages_; }
  std::int64_t other_lines() const { return other_lines_; }

 private:
  std::vector<Trajectory::Message> messages_;
  std::int64_t other_lines_ = 0;
};

class StderrCapture {
 public:
  // From here on fd 2 writes into an anonymous memory file (nothing is captured when one cannot
  // be made: stderr then stays as it was).
  StderrCapture();
  ~StderrCapture();  // restores fd 2 if finish() was not called
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Restores fd 2 and returns what was written meanwhile, counted (empty on a second call).
  CountedLines finish();

 private:
  int saved_ = -1;    // the original fd 2
  int capture_ = -1;  // the memory file
};

}  // namespace dropcheck
