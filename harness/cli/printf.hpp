// printf-style formatting into a std::string of whatever length it takes (no fixed buffer to
// overflow: 1e300 printed with %13.6f is 308 characters).
#pragma once

#include <string>

namespace dropcheck {

// vsnprintf twice: once to measure, once to write.
std::string strprintf(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace dropcheck
