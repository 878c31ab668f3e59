// Comments state the rule they stand for, not the issue or defect that brought it: a number means
// nothing to a reader without the tracker, and the rule outlives it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

namespace fs = std::filesystem;

TEST(SourceComments, CiteNoIssueOrDefectNumbers) {
  const fs::path root(AVK_SOURCE_DIR);
  const std::regex cited(R"(\b([Ii]ssues?|[Dd]efects?) ?#?[0-9]+)");
  std::string found;
  std::size_t files = 0;
  for (const char* folder : {"kinematics", "vehicle", "mission", "store", "sim", "app", "server",
                             "tests", "bench", "web/js", "web/tests", "web/bench", "scripts"}) {
    if (!fs::is_directory(root / folder)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / folder)) {
      const auto ext = e.path().extension();
      if (!e.is_regular_file() || !(ext == ".cpp" || ext == ".hpp" || ext == ".js" ||
                                    ext == ".mjs" || ext == ".txt" || ext.empty()))
        continue;
      ++files;
      std::ifstream in(e.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n)
        if (std::regex_search(line, cited))
          found += fs::relative(e.path(), root).generic_string() + ":" + std::to_string(n) + ": " +
                   line + "\n";
    }
  }
  EXPECT_GT(files, 100u);
  EXPECT_TRUE(found.empty()) << found;
}

}  // namespace
