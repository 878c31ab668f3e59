#include <gtest/gtest.h>

#include <sstream>

#include "server/cli/cli.hpp"

namespace {
int run(const std::vector<std::string>& args, std::string& out, std::string& err,
        const std::string& input = "") {
  std::istringstream in(input);
  std::ostringstream o, e;
  const int rc = avk::server::run_cli(args, in, o, e);
  out = o.str();
  err = e.str();
  return rc;
}
}  // namespace

TEST(Cli, UnknownCommandIsAnErrorThatNamesIt) {
  std::string out, err;
  EXPECT_EQ(run({"frobnicate"}, out, err), 2);
  EXPECT_NE(err.find("frobnicate"), std::string::npos);
}
