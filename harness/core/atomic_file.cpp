#include "harness/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

#include "harness/core/input_error.hpp"
#include "harness/core/signal_cleanup.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The mode a new file gets: 0666 less the umask, or the replaced file's own permissions.
mode_t new_file_mode(const fs::path& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0) return st.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

// Writes all of `content` to `fd`; false with errno set on failure.
bool write_all(int fd, const std::string& content) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// ".<name>.tmp-XXXXXX" beside the target (the name shortened so that it stays a legal name).
std::string temp_template(const fs::path& target) {
  std::string name = target.filename().string().substr(0, 200);
  return (target.parent_path() / ("." + name + ".tmp-XXXXXX")).string();
}

}  // namespace

fs::path output_target(const std::string& path, const std::string& key) {
  fs::path p(path);
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) {
      if (errno == ENOENT || errno == ENOTDIR) return p;  // a new file (or an error at write time)
      throw InputError(path, 0, key, std::string("cannot inspect: ") + std::strerror(errno));
    }
    if (S_ISREG(st.st_mode)) return p;
    if (!S_ISLNK(st.st_mode))
      throw InputError(path, 0, key,
                       std::string("cannot replace the file: it is ") + kind_of(st.st_mode) +
                           "; dropcheck writes only over regular files");
    if (hops == 40) throw InputError(path, 0, key, "too many levels of symbolic links");
    std::error_code ec;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) throw InputError(path, 0, key, "cannot read the symbolic link: " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
}

void write_file_atomic(const std::string& path, const std::string& content) {
  const fs::path target = output_target(path);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  std::string tmp = temp_template(target);
  std::optional<SignalsDeferred> deferred(std::in_place);  // create + register as one step
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw InputError(path, 0, "", std::string("cannot write: ") + std::strerror(errno));
  CleanupOnSignal cleanup(tmp, false);
  deferred.reset();
  const bool written = ::fchmod(fd, new_file_mode(target)) == 0 && write_all(fd, content);
  const int write_errno = errno;
  if (::close(fd) != 0 || !written) {
    const int why = written ? errno : write_errno;
    ::unlink(tmp.c_str());
    throw InputError(path, 0, "", std::string("write failed: ") + std::strerror(why));
  }
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    const int why = errno;
    ::unlink(tmp.c_str());
    throw InputError(path, 0, "", std::string("cannot replace the file: ") + std::strerror(why));
  }
}

}  // namespace dropcheck
