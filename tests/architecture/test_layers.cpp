// The layers of docs/architecture.md, checked on the tree as it is: a file that includes across
// the allowed directions fails CI, naming the file, the line and what it included.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "architecture/layer_check.hpp"
#include "support/temp_dir.hpp"

namespace {

using avk::testing::check_layers;
using avk::testing::parse_layer_rules;
namespace fs = std::filesystem;

std::vector<avk::testing::LayerRule> project_rules() {
  std::ifstream in(fs::path(AVK_SOURCE_DIR) / "tests/architecture/layer_rules.txt");
  EXPECT_TRUE(in) << "tests/architecture/layer_rules.txt is missing";
  return parse_layer_rules(in);
}

}  // namespace

TEST(Layers, TheTreeIncludesOnlyDownward) {
  const auto rules = project_rules();
  ASSERT_GE(rules.size(), 8u);
  std::string report;
  for (const auto& v : check_layers(AVK_SOURCE_DIR, rules))
    report += v.text() + "\n";
  EXPECT_TRUE(report.empty()) << report;
}

TEST(Layers, ADeliberateViolationFailsNamingTheFileTheLineAndTheInclude) {
  // The project's own rules over a small tree: kinematics reaching up into app, the transport
  // reaching into the application, and what is allowed beside them.
  avk::testing::TempDir dir("avk_layers");
  dir.write("kinematics/ckt.hpp",
            "#pragma once\n#include <vector>\n#include \"kinematics/angles.hpp\"\n");
  dir.write("kinematics/angles.hpp", "#pragma once\n#include \"app/context.hpp\"\n");
  dir.write("app/context.hpp",
            "#pragma once\n#include \"store/store.hpp\"\n#include \"kinematics/ckt.hpp\"\n");
  dir.write("server/http/router.cpp",
            "#include \"server/http/router.hpp\"\n#include \"server/api_types.hpp\"\n\n"
            "#include \"app/context.hpp\"\n");
  const auto violations = check_layers(dir.path(), project_rules());
  ASSERT_EQ(violations.size(), 2u);
  EXPECT_EQ(violations[0].file, "kinematics/angles.hpp");
  EXPECT_EQ(violations[0].line, 2);
  EXPECT_EQ(violations[0].included, "app/context.hpp");
  EXPECT_EQ(violations[1].file, "server/http/router.cpp");
  EXPECT_EQ(violations[1].line, 4);
  EXPECT_EQ(violations[1].folder, "server/http");
  EXPECT_NE(violations[1].text().find("server/http/router.cpp:4"), std::string::npos);
}

TEST(Layers, AFrontEndReachingTheStoreThroughAnAppHeaderFails) {
  // A use case's header that keeps the store hidden is the front ends'; one that includes the
  // store (app's own way in) is not, so neither a route nor the command line can name a store type.
  avk::testing::TempDir dir("avk_layers_sealed");
  dir.write("app/turns.hpp", "#pragma once\n#include \"app/turn_views.hpp\"\n");
  dir.write("app/turn_views.hpp", "#pragma once\n#include \"kinematics/turn_sequence.hpp\"\n");
  dir.write("app/store_access.hpp", "#pragma once\n// the door\n#include \"store/store.hpp\"\n");
  dir.write("server/routes/turn_routes.cpp", "#include \"app/turns.hpp\"\n");
  dir.write("server/cli/cmd_turns.cpp",
            "#include \"app/turns.hpp\"\n#include \"app/store_access.hpp\"\n");
  // Through another app header, too.
  dir.write("app/models.hpp", "#pragma once\n#include \"app/store_access.hpp\"\n");
  dir.write("server/routes/model_routes.cpp", "#include \"app/models.hpp\"\n");
  const auto violations = check_layers(dir.path(), project_rules());
  ASSERT_EQ(violations.size(), 2u);
  EXPECT_EQ(violations[1].file, "server/routes/model_routes.cpp");
  EXPECT_EQ(violations[1].included, "app/models.hpp");
  EXPECT_EQ(violations[1].hidden, "store/store.hpp");
  EXPECT_EQ(violations[0].file, "server/cli/cmd_turns.cpp");
  EXPECT_EQ(violations[0].line, 2);
  EXPECT_EQ(violations[0].included, "app/store_access.hpp");
  EXPECT_EQ(violations[0].hidden, "store/store.hpp");
  EXPECT_NE(violations[0].text().find("which includes \"store/store.hpp\""), std::string::npos)
      << violations[0].text();
}

TEST(Layers, AMalformedRuleIsRefusedNamingItsLine) {
  std::istringstream in("kinematics:\nvehicle kinematics\n");
  try {
    parse_layer_rules(in);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}
