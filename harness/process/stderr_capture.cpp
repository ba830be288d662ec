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

std::vector<std::pair<std::string, std::int64_t>> StderrCapture::finish() {
  std::vector<std::pair<std::string, std::int64_t>> lines;
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
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = escape_controls(
        std::string_view(text).substr(start, std::min<std::size_t>(end - start, 300)));
    start = end + 1;
    if (line.empty()) continue;
    auto same =
        std::find_if(lines.begin(), lines.end(), [&](const auto& l) { return l.first == line; });
    if (same != lines.end())
      ++same->second;
    else if (lines.size() < 16)
      lines.emplace_back(std::move(line), 1);
  }
  return lines;
}

}  // namespace dropcheck
