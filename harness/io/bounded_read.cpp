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
  ~FdCloser() { ::close(fd); }
};

}  // namespace

std::string read_regular_file(const std::string& path, std::int64_t max_bytes,
                              const std::string& limit_text, Links links) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one. fstat on
  // what was opened (not on the name, which may change in between) decides before any read.
  // O_NOFOLLOW: a link as the last component fails with ELOOP instead of being opened.
  const int nofollow = links == Links::refuse ? O_NOFOLLOW : 0;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | nofollow);
  if (fd < 0 && errno == ELOOP && links == Links::refuse)
    refuse(path,
           "is a symbolic link; dropcheck never follows a link inside a folder it reads (replace "
           "it with the file itself)");
  if (fd < 0) refuse(path, std::string("cannot read the file: ") + std::strerror(errno));
  const FdCloser closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    refuse(path, std::string("cannot read the file: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) refuse(path, "cannot read the file: it is a directory");
  if (!S_ISREG(st.st_mode))
    refuse(path, "cannot read the file: not a regular file (a device, FIFO or socket)");
  const std::string limit = std::to_string(max_bytes) + " bytes (" + limit_text + ")";
  if (st.st_size > max_bytes)
    refuse(path,
           "the file is " + std::to_string(st.st_size) + " bytes, more than the limit of " + limit);
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

}  // namespace dropcheck
