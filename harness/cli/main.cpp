#include <iostream>

#include "cli.hpp"
#include "harness/run/isolated_run.hpp"

int main(int argc, char** argv) {
  // Every engine run in its own process: an engine's crash or hang is that run's result.
  dropcheck::set_default_isolation(dropcheck::Isolation::child_process);
  return dropcheck::cli_main({argv + 1, argv + argc}, std::cout, std::cerr);
}
