// `avk turns harvest` and `avk ckt build --include-harvested` on a simulated Figure 4-1-kind
// mission: the counts as a table and as JSON, usage errors naming the options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/temp_db.hpp"

namespace {

using avk::testing::run;

TEST(HarvestCli, CountsTheStepsOfAMissionAsTableAndJson) {
  avk::testing::TempDb db("avk_harvest_cli");
  const auto mission =
      run({"mission", "run", "--config", avk::testing::example("thesis-fig4-1.json"), "--db",
           db.path(), "--sim", "--vehicle", "catamaran:m200", "--quiet"});
  ASSERT_EQ(mission.rc, 0) << mission.err;
  const auto table = run({"turns", "harvest", "--db", db.path(), "--mission", "1"});
  ASSERT_EQ(table.rc, 0) << table.err;
  EXPECT_NE(table.out.find("18 already recorded"), std::string::npos) << table.out;
  // Steps no turn is recorded from are listed by reason: Figure 4-1's turn array changes speed
  // twice (0.5 -> 1.0 -> 1.5 m/s), and a step that comes with a new speed is not a turn.
  EXPECT_NE(table.out.find("speed_command_changed"), std::string::npos) << table.out;
  const auto all = run({"turns", "harvest", "--db", db.path(), "--all", "--format", "json"});
  ASSERT_EQ(all.rc, 0) << all.err;
  const auto j = nlohmann::json::parse(all.out);
  ASSERT_EQ(j["missions"].size(), 1u);
  EXPECT_EQ(j["missions"][0]["harvested"], 0);  // the first run found every turn recorded
  EXPECT_EQ(j["missions"][0]["already_recorded"], 18);
  const auto ckt = run(
      {"ckt", "build", "--db", db.path(), "--include-harvested", "--out", db.path() + ".ckt.json"});
  ASSERT_EQ(ckt.rc, 0) << ckt.err;
  EXPECT_NE(ckt.err.find("0 of the turns harvested"), std::string::npos) << ckt.err;

  EXPECT_EQ(run({"turns", "harvest", "--db", db.path()}).rc, 2);
  EXPECT_EQ(run({"turns", "harvest", "--db", db.path(), "--mission", "1", "--all"}).rc, 2);
  EXPECT_EQ(run({"turns", "harvest", "--db", db.path(), "--mission", "1", "--format", "x"}).rc, 2);
  EXPECT_EQ(run({"turns", "list"}).rc, 2);
  EXPECT_EQ(run({"turns", "harvest", "--db", db.path(), "--mission", "9"}).rc, 1);
}

}  // namespace
