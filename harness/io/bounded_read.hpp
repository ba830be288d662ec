// Reading a user's input file with bounded time and memory: only a regular file is read, and only
// up to a size limit, so that /dev/zero, /dev/urandom, a FIFO without a writer or a huge file is
// refused at once with a message instead of hanging or exhausting memory.
#pragma once

#include <cstdint>
#include <string>

#include "harness/io/link_policy.hpp"

namespace dropcheck {

// The bytes of `path`. Throws InputError naming the file, before reading anything, when it cannot
// be opened (the system's reason), is not a regular file (directory, device, FIFO, socket) or is
// larger than `max_bytes`, and when it grows past `max_bytes` while being read. `limit_text` says
// the limit in the message, e.g. "1 MiB, for a scene". With Links::refuse a symbolic link at `path`
// is refused, not followed (an entry of a baseline folder).
std::string read_regular_file(const std::string& path, std::int64_t max_bytes,
                              const std::string& limit_text, Links links = Links::follow);

// A user's input file read line by line, never whole: opened with read_regular_file's checks (a
// regular file no larger than `max_bytes`; with Links::refuse, no link), then streamed through a
// 64 KiB buffer, each line at most `max_line` bytes. So a reader's memory is one line, whatever
// the file holds, and a failure is an error naming the file and line, never the end of the file.
class LineReader {
 public:
  // `what` names the expected content in messages ("a shard file").
  LineReader(const std::string& path, std::int64_t max_bytes, std::size_t max_line,
             std::string what, Links links = Links::follow);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The file's name as messages give it (escaped: harness/core/input_error.hpp).
  const std::string& name() const { return path_; }
  // The next line without its line break (a "\r\n" ends one too); false at the end of the file.
  // Throws InputError naming the file and line: a line longer than max_line, a read error, a file
  // that grew past max_bytes while being read.
  bool next(std::string& line);
  // The number of the line next() returned last (1 for the first).
  long long line_number() const { return line_; }

 private:
  int fill();  // the next byte, or -1 at the end of the file
  std::string path_, what_;
  std::int64_t max_bytes_ = 0, read_ = 0;
  std::size_t max_line_ = 0;
  int fd_ = -1;
  long long line_ = 0;
  std::string buf_;
  std::size_t at_ = 0, end_ = 0;
};

}  // namespace dropcheck
