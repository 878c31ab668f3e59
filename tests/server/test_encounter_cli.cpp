// avk encounter generate|run: the generator's file, the errors of a bad scenario file, and a run
// of two scenarios at a coarse candidate step on a database of analytic turns (never the full
// bench).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using avk::testing::run;
using nlohmann::json;

TEST(EncounterCli, GenerateIsReproducibleForASeed) {
  const auto a = run({"encounter", "generate", "--seed", "4", "--count", "12"});
  const auto b = run({"encounter", "generate", "--seed", "4", "--count", "12"});
  const auto c = run({"encounter", "generate", "--seed", "5", "--count", "12"});
  ASSERT_EQ(a.rc, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
  const json doc = json::parse(a.out);
  EXPECT_EQ(doc["schema_version"], 1);
  EXPECT_EQ(doc["scenarios"].size(), 12u);
  EXPECT_EQ(json::parse(run({"encounter", "generate"}).out)["scenarios"].size(), 60u);
  EXPECT_EQ(run({"encounter", "generate", "--count", "0"}).rc, 2);
}

TEST(EncounterCli, TheCommittedExampleIsTheGeneratorsOutput) {
  const auto g = run({"encounter", "generate", "--seed", "1", "--count", "60"});
  ASSERT_EQ(g.rc, 0);
  std::ifstream f(avk::testing::example("encounters.json"));
  std::stringstream s;
  s << f.rdbuf();
  EXPECT_EQ(s.str(), g.out);
}

class EncounterRun : public ::testing::Test {
 protected:
  void SetUp() override {
    avk::store::Store s(db_.path());
    avk::testing::store_arc_turns(s, "alpha");
  }
  avk::testing::TempDb db_{"avk_encounter_cli"};
};

TEST_F(EncounterRun, ABadScenarioFileNamesItsFields) {
  const auto r = run({"encounter", "run", "--scenarios", "-", "--db", db_.path()},
                     R"({"schema_version": 2, "scenarios": [{"name": "a", "own": {"heading_deg":
                     0, "speed_mps": 1}, "contacts": [{"x_m": 0, "y_m": 30, "course_deg": 180,
                     "speed_mps": -1}]}]})");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("/schema_version"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/scenarios/0/contacts/0/speed_mps"), std::string::npos) << r.err;
}

TEST_F(EncounterRun, RunsEachMethodAndSkipsTheModelWithANote) {
  const std::string scenarios = run({"encounter", "generate", "--seed", "3", "--count", "2"}).out;
  const auto r = run({"encounter", "run", "--scenarios", "-", "--db", db_.path(), "--vehicle",
                      "usim", "--step", "90", "--method", "all", "--format", "json"},
                     scenarios);
  ASSERT_EQ(r.rc, 0) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc["vehicle_id"], "alpha");  // the only vehicle of the database
  EXPECT_EQ(doc["flights"], 2 * 5);
  ASSERT_EQ(doc["scenarios"].size(), 2u);
  EXPECT_EQ(doc["scenarios"][0]["candidates_deg"], json({-180.0, -90.0, 0.0, 90.0, 180.0}));
  EXPECT_EQ(doc["scenarios"][0]["methods"].size(), 2u);  // avk and instantaneous
  EXPECT_EQ(doc["summary"][1]["method"], "model");
  EXPECT_EQ(doc["summary"][1]["available"], false);
  EXPECT_NE(r.err.find("method model skipped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("10 maneuvers flown"), std::string::npos) << r.err;

  const auto table = run({"encounter", "run", "--scenarios", "-", "--db", db_.path(), "--vehicle",
                          "usim", "--step", "90", "--method", "instantaneous"},
                         scenarios);
  ASSERT_EQ(table.rc, 0) << table.err;
  EXPECT_NE(table.out.find("violations"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("instantaneous"), std::string::npos) << table.out;
}

TEST_F(EncounterRun, UsageErrorsNameTheOption) {
  const auto r =
      run({"encounter", "run", "--scenarios", "-", "--db", db_.path(), "--method", "guess"}, "{}");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--method"), std::string::npos) << r.err;
  EXPECT_EQ(run({"encounter", "fly"}).rc, 2);
}

}  // namespace
