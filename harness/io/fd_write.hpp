// Writing to a file descriptor in full: the one loop every writer of pipes and files shares.
#pragma once

#include <cstddef>

namespace dropcheck {

// Writes all `bytes` of `data` to `fd`, retrying after signals (EINTR) and short writes. False,
// with errno set, when a write fails or writes nothing.
bool write_all(int fd, const void* data, std::size_t bytes);

}  // namespace dropcheck
