#include <iostream>

#include "cli.hpp"

int main(int argc, char** argv) {
  return dropcheck::cli_main({argv + 1, argv + argc}, std::cout, std::cerr);
}
