// Drives the command line in-process, as a user would type it: the CLI tests' one entry point.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "harness/cli/cli.hpp"

namespace dropcheck::testing {

// What a command printed and returned.
struct Result {
  int code;
  std::string out, err;
};

// Runs `dropcheck ARGV...` (argv without the program name) and captures both streams.
inline Result cli(const std::vector<std::string>& argv) {
  std::ostringstream out, err;
  const int code = dropcheck::cli_main(argv, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace dropcheck::testing
