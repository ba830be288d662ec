#include "harness/process/stderr_capture.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "harness/core/input_error.hpp"

namespace dropcheck {

StderrCapture::StderrCapture() {
  std::fflush(stderr);
  capture_ = ::memfd_create("dropcheck-stderr", MFD_CLOEXEC);
  if (capture_ < 0) return;
  saved_ = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
  if (saved_ < 0 || ::dup2(capture_, STDERR_FILENO) < 0) {
    if (saved_ >= 0) ::close(saved_);
    ::close(capture_);
    saved_ = capture_ = -1;
  }
}

StderrCapture::~StderrCapture() {
  (void)finish();
}

CountedLines StderrCapture::finish() {
  CountedLines lines;
  if (capture_ < 0) return lines;
  std::fflush(stderr);
  ::dup2(saved_, STDERR_FILENO);
  ::close(saved_);
  std::string text;
  char buf[4096];
  ::lseek(capture_, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(capture_, buf, sizeof buf)) > 0 && text.size() < (1u << 24);)
    text.append(buf, static_cast<std::size_t>(n));
  ::close(capture_);
  saved_ = capture_ = -1;
  lines.add_text(text);
  return lines;
}

void CountedLines::add(std::string_view raw) {
  while (!raw.empty() && (raw.back() == '\r' || raw.back() == ' ')) raw.remove_suffix(1);
  if (raw.empty()) return;
  const bool cut = raw.size() > 300;
  const std::string line = escape_controls(raw.substr(0, 300)) + (cut ? "..." : "");
  for (Trajectory::Message& m : messages_)
    if (m.text == line) {
      ++m.count;
      return;
    }
  if (messages_.size() < Trajectory::kKeptMessages)
    messages_.push_back({line, 1});
  else
    ++other_lines_;
}

void CountedLines::add_text(std::string_view text) {
  while (!text.empty()) {
    const std::size_t end = std::min(text.find('\n'), text.size());
    add(text.substr(0, end));
    text.remove_prefix(std::min(end + 1, text.size()));
  }
}

}  // namespace dropcheck
