// Whether gnuplot is on the PATH: the report's plots are drawn only where it is.
#pragma once

#include <cstdlib>

inline bool has_gnuplot() {
  return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}
