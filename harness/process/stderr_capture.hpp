// This process's stderr (fd 2) taken into memory for a while: what an in-process engine prints
// while it is timed (harness/study/evaluate.cpp time_evaluations), kept from the terminal and
// counted, as an isolated run's stderr is (Trajectory::messages).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dropcheck {

class StderrCapture {
 public:
  // From here on fd 2 writes into an anonymous memory file (nothing is captured when one cannot
  // be made: stderr then stays as it was).
  StderrCapture();
  ~StderrCapture();  // restores fd 2 if finish() was not called
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Restores fd 2 and returns what was written meanwhile, each distinct non-empty line once with
  // its count, in order of first appearance (the first 16; lines cut to 300 bytes, controls
  // escaped).
  std::vector<std::pair<std::string, std::int64_t>> finish();

 private:
  int saved_ = -1;    // the original fd 2
  int capture_ = -1;  // the memory file
};

}  // namespace dropcheck
