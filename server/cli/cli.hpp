#pragma once
// Entry point of the avk command line, callable from tests with string streams.

#include <iosfwd>
#include <string>
#include <vector>

namespace avk::server {

int run_cli(const std::vector<std::string>& args, std::istream& in, std::ostream& out,
            std::ostream& err);

}  // namespace avk::server
