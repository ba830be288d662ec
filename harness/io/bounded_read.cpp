#include "harness/io/bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw InputError(path, 0, "", why);
}

// Closes a file descriptor at scope exit.
struct FdCloser {
  int fd;
  ~FdCloser() {
    if (fd >= 0) ::close(fd);
  }
};

// Opens `path` for reading after the checks read_regular_file documents; the caller closes it.
// `shown`: the path as messages name it.
int open_regular(const std::string& path, const std::string& shown, std::int64_t max_bytes,
                 const std::string& limit, Links links) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one. fstat on
  // what was opened (not on the name, which may change in between) decides before any read.
  // O_NOFOLLOW: a link as the last component fails with ELOOP instead of being opened.
  const int nofollow = links == Links::refuse ? O_NOFOLLOW : 0;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | nofollow);
  if (fd < 0 && errno == ELOOP && links == Links::refuse)
    refuse(shown,
           "is a symbolic link; dropcheck never follows a link inside a folder it reads (replace "
           "it with the file itself)");
  if (fd < 0) refuse(shown, std::string("cannot read the file: ") + std::strerror(errno));
  FdCloser closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    refuse(shown, std::string("cannot read the file: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) refuse(shown, "cannot read the file: it is a directory");
  if (!S_ISREG(st.st_mode))
    refuse(shown, "cannot read the file: not a regular file (a device, FIFO or socket)");
  if (st.st_size > max_bytes)
    refuse(shown,
           "the file is " + std::to_string(st.st_size) + " bytes, more than the limit of " + limit);
  closer.fd = -1;
  return fd;
}

}  // namespace

std::string read_regular_file(const std::string& path, std::int64_t max_bytes,
                              const std::string& limit_text, Links links) {
  const std::string limit = std::to_string(max_bytes) + " bytes (" + limit_text + ")";
  const int fd = open_regular(path, path, max_bytes, limit, links);
  const FdCloser closer{fd};
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(path, std::string("cannot read the file: ") + std::strerror(errno));
    if (n == 0) return text;
    text.append(buf, static_cast<std::size_t>(n));
    if (static_cast<std::int64_t>(text.size()) > max_bytes)
      refuse(path, "the file grew past the limit of " + limit + " while being read");
  }
}

LineReader::LineReader(const std::string& path, std::int64_t max_bytes, std::size_t max_line,
                       std::string what, Links links)
    : path_(escape_controls(path)),
      what_(std::move(what)),
      max_bytes_(max_bytes),
      max_line_(max_line) {
  fd_ = open_regular(path, path_, max_bytes, std::to_string(max_bytes) + " bytes, for " + what_,
                     links);
  buf_.resize(65536);
}

LineReader::~LineReader() {
  ::close(fd_);
}

int LineReader::fill() {
  if (at_ == end_) {
    ssize_t n = 0;
    do n = ::read(fd_, buf_.data(), buf_.size());
    while (n < 0 && errno == EINTR);
    if (n < 0)
      throw InputError(path_, static_cast<int>(line_), "",
                       std::string("cannot read the file: ") + std::strerror(errno));
    read_ += n;
    if (read_ > max_bytes_)
      throw InputError(path_, 0, "",
                       "the file grew past the limit of " + std::to_string(max_bytes_) +
                           " bytes while being read");
    at_ = 0;
    end_ = static_cast<std::size_t>(n);
    if (n == 0) return -1;
  }
  return static_cast<unsigned char>(buf_[at_++]);
}

bool LineReader::next(std::string& line) {
  line.clear();
  int c = fill();
  if (c < 0) return false;
  ++line_;
  for (; c >= 0 && c != '\n'; c = fill()) {
    if (line.size() == max_line_)
      throw InputError(path_, static_cast<int>(line_), "",
                       "a line longer than " + std::to_string(max_line_) + " bytes: not " + what_);
    line.push_back(static_cast<char>(c));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

}  // namespace dropcheck
