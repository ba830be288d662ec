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

}  // namespace dropcheck
