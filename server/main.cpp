#include <iostream>
#include <string>
#include <vector>

#include "server/cli/cli.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return avk::server::run_cli(args, std::cin, std::cout, std::cerr);
}
