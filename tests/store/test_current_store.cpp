// The current a mission flew in and its turns in the water frame: stored in one
// transaction, read back as the table reads them, and a database of the schema before them
// upgrades with everything it held.
#include <gtest/gtest.h>

#include "support/store_engines.hpp"

#include <string>

#include "kinematics/water_frame.hpp"
#include "store/sqlite.hpp"
#include "store/store.hpp"
#include "support/schema_downgrade.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using avk::kinematics::WaterCurrent;
using namespace avk::store;

TurnSequence arc(double dheading_deg, unsigned seed) {
  avk::testing::ArcTurnSpec spec;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.position_noise_m = 0.05;
  spec.start = {3.0, 4.0, 20.0 * seed};
  spec.vehicle_id = "usim-1";
  return avk::testing::make_arc_turn(spec);
}

StoredCurrent current_of(std::int64_t mission, double east, double north) {
  StoredCurrent c;
  c.mission_id = mission;
  c.t_s = 12.5;
  c.estimate.east_mps = east;
  c.estimate.north_mps = north;
  c.estimate.covariance = {1e-4, 2e-5, 3e-4};
  c.estimate.legs = 9;
  c.estimate.speed_scale = 1.02;
  c.estimate.residual_rms_mps = 0.01;
  return c;
}

class CurrentStoreOnEngine : public avk::testing::OnEachEngine {};
AVK_ON_EACH_ENGINE(CurrentStoreOnEngine);

TEST_P(CurrentStoreOnEngine, EstimateAndWaterTurnsRoundTripAndTheGroundFormStays) {
  Store s(db());
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const auto m = s.missions().create("usim-1", "collection", "{}");
  const TurnSequence raw = arc(90.0, 1);
  const auto id = s.turns().add(m, raw, TurnStatus::ok, "");
  EXPECT_FALSE(s.currents().for_mission(m));
  EXPECT_EQ(s.currents().revision("usim-1"), 0);

  const WaterCurrent c{0.1, -0.2};
  const TurnSequence water = avk::kinematics::in_water_frame(raw, c).normalized();
  const auto rev = s.currents().save(current_of(m, c.east_mps, c.north_mps), {{id, water}});
  EXPECT_GT(rev, 0);
  EXPECT_EQ(s.currents().revision("usim-1"), rev);
  const auto got = s.currents().for_mission(m);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->estimate.east_mps, 0.1);
  EXPECT_EQ(got->estimate.covariance[1], 2e-5);
  EXPECT_EQ(got->estimate.legs, 9u);
  EXPECT_EQ(got->method, "legs");
  EXPECT_EQ(got->revision, rev);
  EXPECT_EQ(s.currents().latest_for_vehicle("usim-1")->mission_id, m);
  EXPECT_FALSE(s.currents().latest_for_vehicle("other"));

  const auto as_water =
      s.turns().load_normalized({m}, "usim-1", false, TurnFrameChoice::water_where_known);
  ASSERT_EQ(as_water.size(), 1u);
  EXPECT_EQ(as_water[0], water);
  const auto as_ground = s.turns().load_normalized({m}, "usim-1");
  ASSERT_EQ(as_ground.size(), 1u);
  EXPECT_EQ(as_ground[0], raw.normalized());

  // A new estimate without water turns (no longer significant) takes the water form away.
  const auto rev2 = s.currents().save(current_of(m, 0.01, 0.0), {});
  EXPECT_GT(rev2, rev);
  EXPECT_EQ(s.turns().load_normalized({m}, "usim-1", false, TurnFrameChoice::water_where_known)[0],
            raw.normalized());
}

TEST_P(CurrentStoreOnEngine, AnotherMissionsTurnIsRefusedAndNothingChanges) {
  Store s(db());
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const auto m = s.missions().create("usim-1", "a", "{}");
  const auto other = s.missions().create("usim-1", "b", "{}");
  const TurnSequence raw = arc(45.0, 2);
  const auto mine = s.turns().add(m, raw, TurnStatus::ok, "");
  const auto theirs = s.turns().add(other, raw, TurnStatus::ok, "");
  const TurnSequence water = avk::kinematics::in_water_frame(raw, {0.2, 0.0}).normalized();
  s.currents().save(current_of(m, 0.2, 0.0), {{mine, water}});
  EXPECT_THROW(s.currents().save(current_of(m, 0.3, 0.0), {{mine, water}, {theirs, water}}),
               StoreError);
  EXPECT_EQ(s.currents().for_mission(m)->estimate.east_mps, 0.2);
  EXPECT_EQ(s.turns().load_normalized({m}, "usim-1", false, TurnFrameChoice::water_where_known)[0],
            water);
  EXPECT_EQ(
      s.turns().load_normalized({other}, "usim-1", false, TurnFrameChoice::water_where_known)[0],
      raw.normalized());
}

// A file exactly as schema 9 left it (every step before the currents), a turn stored then.
TEST(CurrentStore, MigratesASchemaNineDatabase) {
  avk::testing::TempDb db("avk_store_current_migration");
  const TurnSequence raw = arc(120.0, 3);
  std::int64_t id = 0;
  {
    Store s(db.path());
    s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
    const auto m = s.missions().create("usim-1", "old", "{}");
    id = s.turns().add(m, raw, TurnStatus::ok, "");
  }
  {
    // Undo the newest step by hand, as if the file had been written before it existed.
    Connection c(db.path());
    avk::testing::downgrade_schema(c, 9);
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  EXPECT_TRUE(s.integrity_check());
  const auto turn = s.turns().get(id);
  ASSERT_TRUE(turn);
  EXPECT_EQ(turn->raw.meta().goal_dheading_deg, raw.meta().goal_dheading_deg);
  const auto loaded =
      s.turns().load_normalized({}, "usim-1", false, TurnFrameChoice::water_where_known);
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_FALSE(loaded[0].meta().removed_current);
  EXPECT_FALSE(s.currents().latest_for_vehicle("usim-1"));
}

// The speed reference and drift scatter judged in a current travel with it; an estimate without
// them reads back without them, and an undetermined reference stays undetermined.
TEST_P(CurrentStoreOnEngine, SpeedReferenceAndDriftScatterRoundTrip) {
  Store s(db());
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const auto a = s.missions().create("usim-1", "a", "{}");
  const auto b = s.missions().create("usim-1", "b", "{}");
  const auto other = s.missions().create("usim-1", "c", "{}");
  StoredCurrent ca = current_of(a, 0.2, 0.1);
  ca.speed_reference = avk::kinematics::SpeedReferenceEvidence{
      7, 0.012, 0.15, 0.14, avk::kinematics::SpeedReference::through_water};
  ca.drift_scatter = avk::kinematics::DriftScatter{0.04, 0.03, 6, 12.5};
  s.currents().save(ca, {});
  StoredCurrent cb = current_of(b, 0.01, 0.0);
  cb.speed_reference = avk::kinematics::SpeedReferenceEvidence{4, 0.05, 0.051, 0.004, {}};
  s.currents().save(cb, {});
  s.currents().save(current_of(other, 0.0, 0.02), {});

  const auto got_a = s.currents().for_mission(a);
  ASSERT_TRUE(got_a);
  EXPECT_EQ(got_a->speed_reference, ca.speed_reference);
  EXPECT_EQ(got_a->drift_scatter, ca.drift_scatter);
  const auto got_b = s.currents().for_mission(b);
  ASSERT_TRUE(got_b && got_b->speed_reference);
  EXPECT_EQ(got_b->speed_reference, cb.speed_reference);
  EXPECT_FALSE(got_b->speed_reference->identified);
  EXPECT_FALSE(got_b->drift_scatter);
  const auto got_other = s.currents().for_mission(other);
  EXPECT_FALSE(got_other->speed_reference);
  EXPECT_FALSE(got_other->drift_scatter);

  const auto all = s.currents().for_vehicle("usim-1");
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].mission_id, a);
  EXPECT_EQ(all[2].mission_id, other);
  EXPECT_LT(all[0].revision, all[1].revision);
  EXPECT_TRUE(s.currents().for_vehicle("nobody").empty());
}

// A file as schema 11 left it, with an estimate stored then: it upgrades, the estimate reads back
// without a speed reference or scatter, and a new save carries them.
TEST(CurrentStore, MigratesASchemaElevenDatabase) {
  avk::testing::TempDb db("avk_store_motion_migration");
  std::int64_t m = 0;
  {
    Store s(db.path());
    s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
    m = s.missions().create("usim-1", "old", "{}");
  }
  {
    Connection c(db.path());
    avk::testing::downgrade_schema(c, 11);
    c.exec(
        "INSERT INTO mission_currents (mission_id, t_s, method, east_mps, north_mps, cov_ee, "
        "cov_en, cov_nn, speed_scale, residual_rms_mps, evidence, revision) VALUES "
        "(1, 5.0, 'legs', 0.2, -0.1, 1e-4, 0, 1e-4, 1.0, 0.01, 12, 3)");
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  EXPECT_TRUE(s.integrity_check());
  const auto old = s.currents().for_mission(m);
  ASSERT_TRUE(old);
  EXPECT_EQ(old->estimate.east_mps, 0.2);
  EXPECT_EQ(old->estimate.legs, 12u);
  EXPECT_FALSE(old->speed_reference);
  EXPECT_FALSE(old->drift_scatter);
  StoredCurrent fresh = *old;
  fresh.speed_reference = avk::kinematics::SpeedReferenceEvidence{
      5, 0.02, 0.2, 0.15, avk::kinematics::SpeedReference::over_ground};
  fresh.drift_scatter = avk::kinematics::DriftScatter{0.08, 0.05, 5, 7.0};
  EXPECT_GT(s.currents().save(fresh, {}), 3);
  EXPECT_EQ(s.currents().for_mission(m)->speed_reference, fresh.speed_reference);
  EXPECT_EQ(s.currents().for_mission(m)->drift_scatter, fresh.drift_scatter);
}

}  // namespace
