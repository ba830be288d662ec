#include "harness/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <streambuf>
#include <string_view>
#include <vector>

#include "harness/core/input_error.hpp"
#include "harness/io/fd_write.hpp"
#include "harness/process/signal_cleanup.hpp"

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

// A stream buffer that writes to a file descriptor in blocks of kSize bytes. The first failed
// write is kept (errno) and every later one skipped.
class FdBuffer : public std::streambuf {
 public:
  static constexpr std::size_t kSize = 64 * 1024;
  explicit FdBuffer(int fd) : fd_(fd), buffer_(kSize) {
    setp(buffer_.data(), buffer_.data() + kSize);
  }
  int error() const { return error_; }  // errno of the first failed write, 0 if none

 protected:
  int_type overflow(int_type c) override {
    if (!flush()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return flush() ? 0 : -1; }

 private:
  bool flush() {
    const std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    if (error_ == 0 && n > 0 && !write_all(fd_, pbase(), n)) error_ = errno;
    setp(buffer_.data(), buffer_.data() + kSize);
    return error_ == 0;
  }
  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

// ".<name>.tmp-XXXXXX" beside the target (the name shortened so that it stays a legal name).
std::string temp_template(const fs::path& target) {
  std::string name = target.filename().string().substr(0, 200);
  return (target.parent_path() / ("." + name + ".tmp-XXXXXX")).string();
}

}  // namespace

fs::path output_target(const std::string& path, const std::string& key, Links links) {
  fs::path p(path);
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) {
      if (errno == ENOENT || errno == ENOTDIR) return p;  // a new file (or an error at write time)
      throw InputError(path, 0, key, std::string("cannot inspect: ") + std::strerror(errno));
    }
    if (S_ISREG(st.st_mode)) return p;
    if (S_ISLNK(st.st_mode) && links == Links::refuse)
      throw InputError(path, 0, key,
                       "is a symbolic link; dropcheck never writes through a link in a folder it "
                       "fills (remove the link, or write elsewhere)");
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

void check_no_links_below(const fs::path& root, const fs::path& path, const std::string& key) {
  const fs::path rel = path.lexically_normal().lexically_relative(root.lexically_normal());
  if (rel.empty() || *rel.begin() == "..")
    throw InputError(path.string(), 0, key, "lies outside '" + root.string() + "'");
  fs::path at = root;
  for (const fs::path& part : rel.parent_path()) {
    at /= part;
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) {
      if (errno == ENOENT) return;  // made later, as a folder
      throw InputError(at.string(), 0, key, std::string("cannot inspect: ") + std::strerror(errno));
    }
    if (S_ISLNK(st.st_mode))
      throw InputError(at.string(), 0, key,
                       "is a symbolic link inside a folder dropcheck fills; it never writes "
                       "through one (remove the link)");
    if (!S_ISDIR(st.st_mode))
      throw InputError(at.string(), 0, key,
                       std::string("is ") + kind_of(st.st_mode) + ", where a folder is expected");
  }
}

void write_file_atomic(const std::string& path, const std::string& content, Links links) {
  write_file_atomic(
      path, [&](std::ostream& out) { out.write(content.data(), content.size()); }, links);
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill,
                       Links links) {
  const fs::path target = output_target(path, "", links);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  std::string tmp = temp_template(target);
  std::optional<SignalsDeferred> deferred(std::in_place);  // create + register as one step
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw InputError(path, 0, "", std::string("cannot write: ") + std::strerror(errno));
  CleanupOnSignal cleanup(tmp, false);
  deferred.reset();
  int why = ::fchmod(fd, new_file_mode(target)) == 0 ? 0 : errno;
  if (why == 0) {
    FdBuffer buffer(fd);
    std::ostream out(&buffer);
    try {
      fill(out);
    } catch (...) {
      ::close(fd);
      ::unlink(tmp.c_str());
      throw;
    }
    out.flush();
    why = buffer.error();
  }
  if (::close(fd) != 0 && why == 0) why = errno;
  if (why != 0) {
    ::unlink(tmp.c_str());
    throw InputError(path, 0, "", std::string("write failed: ") + std::strerror(why));
  }
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    why = errno;
    ::unlink(tmp.c_str());
    throw InputError(path, 0, "", std::string("cannot replace the file: ") + std::strerror(why));
  }
}

}  // namespace dropcheck
