// Comments state the rule they stand for, not the issue or defect that brought it: a number means
// nothing to a reader without the tracker, and the rule outlives it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "architecture/layer_check.hpp"

namespace {

namespace fs = std::filesystem;

TEST(SourceComments, CiteNoIssueOrDefectNumbers) {
  const fs::path root(AVK_SOURCE_DIR);
  const std::regex cited(R"(\b([Ii]ssues?|[Dd]efects?) ?#?[0-9]+)");
  std::string found;
  const auto paths = avk::testing::source_files(
      root,
      {"kinematics", "vehicle", "mission", "store", "sim", "app", "server", "tests", "bench",
       "web/js", "web/tests", "web/bench", "scripts"},
      {".cpp", ".hpp", ".js", ".mjs", ".txt", ""});
  for (const auto& path : paths) {
    std::ifstream in(path);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (std::regex_search(line, cited))
        found += fs::relative(path, root).generic_string() + ":" + std::to_string(n) + ": " + line +
                 "\n";
  }
  const std::size_t files = paths.size();
  EXPECT_GT(files, 100u);
  EXPECT_TRUE(found.empty()) << found;
}

}  // namespace
