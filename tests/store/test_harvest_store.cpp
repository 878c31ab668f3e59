// Harvested turns in the store: their source and quality, the CKT's turns
// with or without them, harvest runs, and a database of the previous schema upgrading.
#include <gtest/gtest.h>

#include "support/store_engines.hpp"

#include <string>

#include "kinematics/turn_json.hpp"
#include "store/sqlite.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnSource;
using avk::kinematics::TurnStatus;
using avk::testing::TempDb;
using namespace avk::store;

TurnSequence arc(double dheading_deg, unsigned seed) {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = 1.0;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.start = {1.0, 2.0, 10.0 * seed};
  spec.vehicle_id = "m200";
  return avk::testing::make_arc_turn(spec);
}

TurnSequence harvested(TurnSequence t, double quality) {
  t.meta().source = TurnSource::harvested;
  t.meta().quality = quality;
  return t;
}

class HarvestStoreOnEngine : public avk::testing::OnEachEngine {};
AVK_ON_EACH_ENGINE(HarvestStoreOnEngine);

TEST_P(HarvestStoreOnEngine, TheCktLoadsCollectionTurnsUnlessAskedForHarvestedOnes) {
  Store s(db());
  s.vehicles().upsert({"m200", "catamaran", 2.0, 1.0});
  const auto mission = s.missions().create("m200", "log", "{}");
  const auto collected = s.turns().add(mission, arc(90.0, 1), TurnStatus::ok, "");
  EXPECT_EQ(s.turns().newest_ok_id("m200"), collected);
  const auto picked = s.turns().add(mission, harvested(arc(60.0, 2), 0.75), TurnStatus::ok, "");
  EXPECT_EQ(s.turns().newest_ok_id("m200"), collected);
  EXPECT_EQ(s.turns().newest_ok_id("m200", true), picked);

  ASSERT_EQ(s.turns().load_normalized({}, "m200").size(), 1u);
  const auto both = s.turns().load_normalized({mission}, "m200", true);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].meta().source, TurnSource::harvested);
  EXPECT_EQ(both[1].meta().quality, 0.75);

  const auto rows = s.turns().list({});
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].source, TurnSource::collection);
  EXPECT_FALSE(rows[0].quality);
  EXPECT_EQ(rows[1].source, TurnSource::harvested);
  EXPECT_EQ(rows[1].quality, 0.75);
  EXPECT_EQ(s.turns().get(picked)->raw.meta().source, TurnSource::harvested);
  EXPECT_EQ(s.turns().start_times(mission).size(), 2u);
}

TEST_P(HarvestStoreOnEngine, HarvestRunsAreKeptWithTheirCounts) {
  Store s(db());
  s.vehicles().upsert({"m200", "catamaran", 2.0, 1.0});
  const auto mission = s.missions().create("m200", "log", "{}");
  HarvestRecord h;
  h.mission_id = mission;
  h.steps = 9;
  h.harvested = 3;
  h.already_recorded = 2;
  h.rejected = {{"not_steady_before", 3}, {"too_small", 1}};
  const auto id = s.harvests().save(h);
  const auto runs = s.harvests().list(mission);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].id, id);
  EXPECT_EQ(runs[0].steps, 9);
  EXPECT_EQ(runs[0].harvested, 3);
  EXPECT_EQ(runs[0].already_recorded, 2);
  EXPECT_EQ(runs[0].rejected, h.rejected);
  EXPECT_FALSE(runs[0].created_utc.empty());
  EXPECT_TRUE(s.harvests().list(mission + 1).empty());
}

// A file as schema 7 left it: its turns become collection turns without quality, and keep
// building the table.
TEST(HarvestStore, ASchemaSevenDatabaseUpgradesAndKeepsItsTurns) {
  TempDb db;
  const TurnSequence old = arc(90.0, 3);
  {
    Connection c(db.path());
    for (int i = 0; i < 7; ++i)
      c.exec(std::string(migration_step_sql(i)).c_str());
    c.exec("PRAGMA user_version = 7");
    c.exec("INSERT INTO vehicles (id, kind, max_speed_mps) VALUES ('m200', 'catamaran', 2)");
    c.exec(
        "INSERT INTO missions (id, vehicle_id, name, config_json, status) "
        "VALUES (4, 'm200', 'old', '{}', 'done')");
    TurnSequence raw = old;
    raw.meta().status = TurnStatus::ok;
    c.prepare(
         "INSERT INTO turns (mission_id, vehicle_id, cell_speed_mps, cell_dheading_deg, status, "
         "reason, commanded_speed_mps, goal_dheading_deg, observed_dheading_deg, start_time_s, "
         "end_time_s, raw_json, normalized_json) "
         "VALUES (4, 'm200', 1, 90, 'ok', '', 1, 90, 90, 0, 10, ?, ?)")
        .bind(1, avk::kinematics::to_json_string(raw))
        .bind(2, avk::kinematics::to_json_string(raw.normalized()))
        .run();
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  EXPECT_TRUE(s.integrity_check());
  const auto rows = s.turns().list({});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].source, TurnSource::collection);
  EXPECT_FALSE(rows[0].quality);
  ASSERT_EQ(s.turns().load_normalized({}, "m200").size(), 1u);
  EXPECT_EQ(s.turns().load_normalized({}, "m200")[0], old.normalized());
  s.turns().add(4, harvested(arc(45.0, 5), 0.5), TurnStatus::ok, "");
  EXPECT_EQ(s.turns().load_normalized({}, "m200").size(), 1u);
  EXPECT_EQ(s.turns().load_normalized({}, "m200", true).size(), 2u);
  HarvestRecord h;
  h.mission_id = 4;
  EXPECT_GT(s.harvests().save(h), 0);
  // The column refuses a source outside the list.
  EXPECT_THROW(Connection(db.path()).exec("UPDATE turns SET source = 'guessed'"), StoreError);
}

}  // namespace
