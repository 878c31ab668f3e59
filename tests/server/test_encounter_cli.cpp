// avk encounter generate|run and avk maneuver fly: the generator's file, the errors of a bad
// scenario file, a run of two scenarios at a coarse candidate step on a database of analytic turns
// (never the full bench), and one candidate flown alone exactly as the bench flew it.
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

// Calm water, no turn: the track is the straight line along the heading at the own speed, and a
// contact crossing 10 m to the side passes at exactly 10 m when it is abeam (t = 50 m / 2 m/s).
TEST(ManeuverFly, HoldingCourseInCalmWaterGoesStraight) {
  const auto r = run({"maneuver", "fly", "--vehicle", "usim", "--own", "90,1", "--dheading", "0",
                      "--contact", "50,10,270,1", "--horizon", "60"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const json doc = json::parse(r.out);
  const json& track = doc["track"];
  ASSERT_GT(track.size(), 100u);
  EXPECT_EQ(track.front(), json({0.0, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(track.back()[0].get<double>(), 60.0);
  double last_x = -1.0;
  for (const json& p : track) {
    EXPECT_NEAR(p[2].get<double>(), 0.0, 1e-6) << p;  // due east: no northing
    EXPECT_GT(p[1].get<double>(), last_x) << p;
    EXPECT_NEAR(p[1].get<double>(), p[0].get<double>(), 0.5) << p;  // 1 m/s
    last_x = p[1].get<double>();
  }
  ASSERT_EQ(doc["cpa"].size(), 1u);
  EXPECT_NEAR(doc["cpa"][0]["distance_m"].get<double>(), 10.0, 1e-6);
  EXPECT_NEAR(doc["cpa"][0]["time_s"].get<double>(), 25.0, 0.5);
  EXPECT_EQ(doc["seed"], 1);
  EXPECT_EQ(doc["sim_vehicle"], "usim");

  const auto csv = run({"maneuver", "fly", "--vehicle", "usim", "--own", "90,1", "--dheading", "0",
                        "--contact", "50,10,270,1", "--horizon", "60", "--format", "csv"});
  ASSERT_EQ(csv.rc, 0) << csv.err;
  EXPECT_EQ(csv.out.rfind("t_s,x_m,y_m\n0.0,0.0,0.0\n", 0), 0u) << csv.out.substr(0, 40);
  EXPECT_NE(csv.err.find("CPA 10.0 m"), std::string::npos) << csv.err;
}

TEST(ManeuverFly, UsageErrorsNameTheOption) {
  const auto no_dheading = run({"maneuver", "fly", "--own", "0,1", "--contact", "0,30,180,1"});
  EXPECT_EQ(no_dheading.rc, 2);
  EXPECT_NE(no_dheading.err.find("--dheading"), std::string::npos) << no_dheading.err;
  const auto bad = run({"maneuver", "fly", "--vehicle", "usim", "--own", "0,-1", "--dheading", "30",
                        "--contact", "0,30,180,1"});
  EXPECT_EQ(bad.rc, 1);
  EXPECT_NE(bad.err.find("/own/speed_mps"), std::string::npos) << bad.err;
}

// The bench's flown CPA of a candidate is what `avk maneuver fly` flies for it: same setup, same
// seed (the bench's default, 1), same scenario.
TEST_F(EncounterRun, FlyFliesACandidateAsTheBenchFlewIt) {
  const std::string scenarios = R"({"schema_version": 1, "standoff_m": 8, "horizon_s": 60,
    "scenarios": [{"name": "crossing", "own": {"heading_deg": 20, "speed_mps": 1.2},
    "contacts": [{"x_m": 30, "y_m": 25, "course_deg": 270, "speed_mps": 0.9}]}]})";
  const auto bench = run({"encounter", "run", "--scenarios", "-", "--db", db_.path(), "--vehicle",
                          "usim", "--step", "90", "--method", "instantaneous", "--format", "json"},
                         scenarios);
  ASSERT_EQ(bench.rc, 0) << bench.err;
  const json s = json::parse(bench.out)["scenarios"][0];
  ASSERT_EQ(s["candidates_deg"], json({-180.0, -90.0, 0.0, 90.0, 180.0}));
  for (const std::size_t i : {1u, 2u, 3u}) {
    const double dheading = s["candidates_deg"][i].get<double>();
    const auto fly =
        run({"maneuver", "fly", "--vehicle", "usim", "--own", "20,1.2", "--dheading",
             std::to_string(dheading), "--contact", "30,25,270,0.9", "--horizon", "60"});
    ASSERT_EQ(fly.rc, 0) << fly.err;
    EXPECT_DOUBLE_EQ(json::parse(fly.out)["min_cpa_m"].get<double>(),
                     s["flown_cpa_m"][i].get<double>())
        << "dheading " << dheading;
  }
}

}  // namespace
