#pragma once
// Runs the avk command line in-process, as the server tests do, and finds the example files.

#include <sstream>
#include <string>
#include <vector>

#include "server/cli/cli.hpp"

namespace avk::testing {

struct CliResult {
  int rc;
  std::string out;
  std::string err;
};

inline CliResult run(const std::vector<std::string>& args, const std::string& input = "") {
  std::istringstream in(input);
  std::ostringstream o, e;
  const int rc = avk::server::run_cli(args, in, o, e);
  return {rc, o.str(), e.str()};
}

inline std::string example(const std::string& name) {
  return std::string(AVK_SOURCE_DIR) + "/examples/" + name;
}

}  // namespace avk::testing
