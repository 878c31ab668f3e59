#include <gtest/gtest.h>

#include "support/store_engines.hpp"

#include "support/temp_db.hpp"

#include <atomic>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_json.hpp"
#include "store/postgresql.hpp"
#include "store/sqlite.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using namespace avk::store;

namespace {

using avk::testing::TempDb;

std::int64_t make_mission(Store& s, const std::string& vehicle = "usim-1") {
  s.vehicles().upsert({vehicle, "usim", 2.0, 1.2});
  return s.missions().create(vehicle, "collection", R"({"speeds":[1.0]})");
}

TurnSequence arc(double speed_mps, double dheading_deg, unsigned seed = 1) {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = speed_mps;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.position_noise_m = 0.01;
  spec.start = {12.5, -3.25, 33.0};
  return avk::testing::make_arc_turn(spec);
}

std::vector<NavRow> nav_rows(int n, double t0_s = 0.0) {
  std::vector<NavRow> rows;
  for (int i = 0; i < n; ++i)
    rows.push_back({t0_s + 0.1 * i, 0.5 * i, -0.25 * i, std::fmod(3.0 * i, 360.0), 1.0,
                    i % 2 ? std::optional<double>(90.0) : std::nullopt, 1.0, "turn"});
  return rows;
}

}  // namespace

class StoreOnEngine : public avk::testing::OnEachEngine {};
AVK_ON_EACH_ENGINE(StoreOnEngine);

TEST_P(StoreOnEngine, MigrationCreatesSchemaAndVersion) {
  Store s(db());
  EXPECT_EQ(s.user_version(), schema_version());
  EXPECT_GE(schema_version(), 1);
  const auto m = make_mission(s);
  EXPECT_TRUE(s.turns().list({}).empty());
  EXPECT_TRUE(s.navigation().for_mission(m).empty());
  EXPECT_FALSE(s.ckt_snapshots().latest("").has_value());
}

TEST(Store, FileDatabaseUsesWal) {
  TempDb db;
  Store s(db.path());
  EXPECT_EQ(s.journal_mode(), "wal");
  EXPECT_TRUE(s.integrity_check());
}

TEST_P(StoreOnEngine, ReopeningKeepsData) {
  std::int64_t mission = 0, turn = 0;
  {
    Store s(db());
    mission = make_mission(s);
    turn = s.turns().add(mission, arc(1.0, 90.0), TurnStatus::ok, "");
  }
  Store s(db());
  EXPECT_EQ(s.user_version(), schema_version());
  ASSERT_TRUE(s.missions().get(mission));
  EXPECT_EQ(s.missions().get(mission)->name, "collection");
  ASSERT_TRUE(s.turns().get(turn));
  EXPECT_EQ(s.vehicles().get("usim-1")->length_m, 1.2);
}

TEST_P(StoreOnEngine, NewerSchemaRefused) {
  { Store s(db()); }
  {
    // Simulates a database written by a future release.
    const std::string newer = std::to_string(schema_version() + 1);
    if (engine() == Engine::sqlite) {
      Connection(db()).exec("PRAGMA user_version = " + newer);
    } else {
      PgConnection c(db());
      c.exec("UPDATE avk_schema SET version = " + newer);
    }
  }
  try {
    Store s(db());
    FAIL() << "a newer database was opened";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("newer than this program supports"), std::string::npos)
        << e.what();
  }
}

TEST_P(StoreOnEngine, MissionLifecycle) {
  Store s(db());
  const auto id = make_mission(s);
  auto m = s.missions().get(id);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->status, MissionStatus::created);
  EXPECT_FALSE(m->created_utc.empty());
  s.missions().set_status(id, MissionStatus::running, "", 1.5);
  s.missions().set_status(id, MissionStatus::paused, "operator", 2.0);
  s.missions().set_status(id, MissionStatus::running, "", 3.0);
  s.missions().set_status(id, MissionStatus::aborted, "link lost", 9.0);
  m = s.missions().get(id);
  EXPECT_EQ(m->status, MissionStatus::aborted);
  EXPECT_EQ(m->status_reason, "link lost");
  EXPECT_EQ(m->started_s, 1.5);
  EXPECT_EQ(m->ended_s, 9.0);
  EXPECT_THROW(s.missions().set_status(id + 100, MissionStatus::done, "", 0.0), StoreError);
  EXPECT_EQ(s.missions().list().size(), 1u);
  for (auto st : {MissionStatus::created, MissionStatus::interrupted, MissionStatus::halted,
                  MissionStatus::done})
    EXPECT_EQ(mission_status_from_string(to_string(st)), st);
  EXPECT_FALSE(mission_status_from_string("bogus"));
}

TEST_P(StoreOnEngine, MissionNeedsKnownVehicle) {
  Store s(db());
  EXPECT_THROW(s.missions().create("ghost", "x", "{}"), StoreError);
  EXPECT_TRUE(s.missions().list().empty());
}

TEST_P(StoreOnEngine, TurnRoundTripIsBitExact) {
  Store s(db());
  const auto mission = make_mission(s);
  const TurnSequence turn = arc(1.25, -70.0, 7);
  const auto id = s.turns().add(mission, turn, TurnStatus::ok, "", {4.75, -1.25, 0.375});
  const auto got = s.turns().get(id);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->raw, turn);
  ASSERT_TRUE(got->normalized);
  EXPECT_EQ(*got->normalized, turn.normalized());
  EXPECT_EQ(avk::kinematics::to_json_string(got->raw), avk::kinematics::to_json_string(turn));
  EXPECT_EQ(got->row.mission_id, mission);
  EXPECT_EQ(got->row.commanded_speed_mps, 1.25);
  EXPECT_EQ(got->row.goal_dheading_deg, -70.0);
  EXPECT_EQ(got->row.cell_dheading_deg, 70.0);
  EXPECT_EQ(got->row.observed_dheading_deg, turn.meta().observed_dheading_deg);
  EXPECT_EQ(got->row.condition_set_time_s, 4.75);
  EXPECT_EQ(got->row.start_heading_error_deg, -1.25);
  EXPECT_EQ(got->row.start_yaw_rate_dps, 0.375);
  ASSERT_TRUE(got->row.advance_m && got->row.transfer_m);
  EXPECT_GT(*got->row.advance_m, 0.0);
  EXPECT_GT(*got->row.transfer_m, 0.0);
  EXPECT_FALSE(s.turns().get(id + 1));
}

TEST_P(StoreOnEngine, AbortedAndRejectedTurnsKeepReasons) {
  Store s(db());
  const auto mission = make_mission(s);
  const auto a = s.turns().add(mission, arc(1.0, 40.0), TurnStatus::aborted, "obstacle ahead");
  // Too short to normalise: still kept, without the normalised form.
  TurnSequence tiny(arc(1.0, 40.0).meta(), {});
  const auto r = s.turns().add(mission, tiny, TurnStatus::rejected, "too few samples");
  const auto ga = s.turns().get(a);
  const auto gr = s.turns().get(r);
  ASSERT_TRUE(ga && gr);
  EXPECT_EQ(ga->row.status, TurnStatus::aborted);
  EXPECT_EQ(ga->row.reason, "obstacle ahead");
  EXPECT_EQ(ga->raw.meta().status, TurnStatus::aborted);
  EXPECT_EQ(ga->raw.meta().status_reason, "obstacle ahead");
  EXPECT_EQ(gr->row.status, TurnStatus::rejected);
  EXPECT_EQ(gr->row.reason, "too few samples");
  EXPECT_FALSE(gr->normalized);
  EXPECT_FALSE(gr->row.advance_m);
  // An ok turn must normalise.
  EXPECT_ANY_THROW(s.turns().add(mission, tiny, TurnStatus::ok, ""));
  EXPECT_EQ(s.turns().list({}).size(), 2u);
}

TEST_P(StoreOnEngine, KeysetPaginationReturnsEveryIdOnceInOrder) {
  Store s(db());
  const auto mission = make_mission(s);
  const TurnSequence turn = arc(1.0, 90.0);
  std::vector<std::int64_t> stored;
  for (int i = 0; i < 250; ++i)
    stored.push_back(s.turns().add(mission, turn, TurnStatus::ok, ""));
  std::vector<std::int64_t> seen;
  TurnFilter f;
  f.limit = 100;
  int pages = 0;
  for (;;) {
    const auto page = s.turns().list(f);
    if (page.empty()) break;
    ++pages;
    EXPECT_LE(page.size(), 100u);
    for (const auto& r : page)
      seen.push_back(r.id);
    f.after_id = page.back().id;
  }
  EXPECT_EQ(pages, 3);
  EXPECT_EQ(seen, stored);
  EXPECT_EQ(std::set<std::int64_t>(seen.begin(), seen.end()).size(), 250u);
}

TEST_P(StoreOnEngine, FiltersByMissionSpeedHeadingStatus) {
  Store s(db());
  const auto m1 = make_mission(s);
  const auto m2 = make_mission(s);
  s.turns().add(m1, arc(1.0, 90.0), TurnStatus::ok, "");
  s.turns().add(m1, arc(1.5, 90.0), TurnStatus::ok, "");
  s.turns().add(m1, arc(1.0, -40.0), TurnStatus::aborted, "halt");
  s.turns().add(m2, arc(1.0, 90.0), TurnStatus::rejected, "noisy");
  auto count = [&](TurnFilter f) { return s.turns().list(f).size(); };
  TurnFilter f;
  EXPECT_EQ(count(f), 4u);
  f.mission_id = m1;
  EXPECT_EQ(count(f), 3u);
  f.speed_mps = 1.02;
  EXPECT_EQ(count(f), 2u);
  f.dheading_deg = 90.0;
  EXPECT_EQ(count(f), 1u);
  f = {};
  f.dheading_deg = -40.0;
  EXPECT_EQ(count(f), 1u);
  f = {};
  f.status = TurnStatus::rejected;
  const auto rej = s.turns().list(f);
  ASSERT_EQ(rej.size(), 1u);
  EXPECT_EQ(rej[0].mission_id, m2);
  EXPECT_EQ(rej[0].reason, "noisy");
  f.mission_id = m1;
  EXPECT_EQ(count(f), 0u);
}

TEST_P(StoreOnEngine, NavBatchAppendReadsBackInOrder) {
  Store s(db());
  const auto m1 = make_mission(s);
  const auto m2 = make_mission(s);
  const auto first = nav_rows(500);
  const auto second = nav_rows(300, 50.0);
  s.navigation().append(m1, first);
  s.navigation().append(m2, nav_rows(10));
  s.navigation().append(m1, second);
  auto expected = first;
  expected.insert(expected.end(), second.begin(), second.end());
  EXPECT_EQ(s.navigation().for_mission(m1), expected);
  EXPECT_EQ(s.navigation().for_mission(m2).size(), 10u);
}

TEST_P(StoreOnEngine, NavForMissingMissionStoresNothing) {
  Store s(db());
  const auto m = make_mission(s);
  EXPECT_THROW(s.navigation().append(m + 1, nav_rows(5)), StoreError);
  EXPECT_TRUE(s.navigation().for_mission(m + 1).empty());
}

TEST_P(StoreOnEngine, TurnForMissingMissionThrowsAndStoresNothing) {
  Store s(db());
  const auto m = make_mission(s);
  EXPECT_THROW(s.turns().add(m + 42, arc(1.0, 90.0), TurnStatus::ok, ""), StoreError);
  EXPECT_TRUE(s.turns().list({}).empty());
  EXPECT_TRUE(s.integrity_check());
}

TEST_P(StoreOnEngine, FailureInsideStoreTurnLeavesNothing) {
  Store s(db());
  const auto m = make_mission(s);
  s.set_store_turn_hook_for_testing([](std::string_view step) {
    if (step == "turn_inserted") throw std::runtime_error("injected failure");
  });
  EXPECT_THROW(s.turns().add(m, arc(1.0, 90.0), TurnStatus::ok, ""), std::runtime_error);
  EXPECT_TRUE(s.turns().list({}).empty());
  // The store stays usable: the rollback released the write transaction.
  s.set_store_turn_hook_for_testing({});
  const auto id = s.turns().add(m, arc(1.0, 90.0), TurnStatus::ok, "");
  EXPECT_EQ(s.turns().list({}).size(), 1u);
  EXPECT_TRUE(s.turns().get(id));
}

TEST_P(StoreOnEngine, ConcurrentReaderSeesCommittedTurns) {
  Store writer(db());
  Store reader(db());
  const auto m = make_mission(writer);
  const auto first = writer.turns().add(m, arc(1.0, 90.0), TurnStatus::ok, "");
  ASSERT_EQ(reader.turns().list({}).size(), 1u);
  EXPECT_EQ(reader.turns().get(first)->raw, arc(1.0, 90.0));
  // While the writer is inside its transaction the reader is not blocked (WAL) and does not see
  // the uncommitted turn.
  std::size_t seen_during_write = 99;
  writer.set_store_turn_hook_for_testing(
      [&](std::string_view) { seen_during_write = reader.turns().list({}).size(); });
  writer.turns().add(m, arc(1.5, 40.0), TurnStatus::ok, "");
  EXPECT_EQ(seen_during_write, 1u);
  EXPECT_EQ(reader.turns().list({}).size(), 2u);
}

TEST_P(StoreOnEngine, CorruptTurnJsonNamesTheTurn) {
  Store s(db());
  const auto m = make_mission(s);
  const auto id = s.turns().add(m, arc(1.0, 90.0), TurnStatus::ok, "");
  s.overwrite_turn_json_for_testing(id, R"({"samples": [1, 2)");
  try {
    s.turns().get(id);
    FAIL() << "corrupt turn was read";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("turn " + std::to_string(id)), std::string::npos)
        << e.what();
  }
  // The summary row is still listable.
  EXPECT_EQ(s.turns().list({}).size(), 1u);
}

TEST_P(StoreOnEngine, CktSnapshotRoundTrip) {
  Store s(db());
  const auto m = make_mission(s);
  const auto turns = avk::testing::thesis_grid_turns(2, 0.25, 0.02);
  const auto table = avk::kinematics::Ckt::build(turns);
  s.ckt_snapshots().save(avk::kinematics::Ckt{}, {});
  const auto id = s.ckt_snapshots().save(table, {m, m + 7});
  const auto snap = s.ckt_snapshots().latest("");
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->id, id);
  EXPECT_EQ(snap->mission_ids, (std::vector<std::int64_t>{m, m + 7}));
  EXPECT_EQ(snap->document, avk::kinematics::ckt_to_json_string(table));
  EXPECT_EQ(avk::kinematics::ckt_to_json_string(snap->table), snap->document);
  EXPECT_EQ(snap->table.grid(), table.grid());
  EXPECT_FALSE(snap->created_utc.empty());
}

TEST_P(StoreOnEngine, IntegrityCheckPasses) {
  Store s(db());
  const auto m = make_mission(s);
  s.turns().add(m, arc(1.0, 90.0), TurnStatus::ok, "");
  s.navigation().append(m, nav_rows(100));
  EXPECT_TRUE(s.integrity_check());
}

// Each vehicle's newest table answers for that vehicle only, whichever was imported last.
TEST_P(StoreOnEngine, CktSnapshotIsTheVehiclesOwn) {
  Store s(db());
  avk::kinematics::Ckt a =
      avk::kinematics::Ckt::build(avk::testing::thesis_grid_turns(1, 0.25, 0.02));
  avk::kinematics::Ckt b = a;
  a.vehicle_id = "alpha";
  b.vehicle_id = "bravo";
  const auto a1 = s.ckt_snapshots().save(a, {});
  const auto b1 = s.ckt_snapshots().save(b, {});
  EXPECT_EQ(s.ckt_snapshots().latest("alpha")->id, a1);
  EXPECT_EQ(s.ckt_snapshots().latest("alpha")->table.vehicle_id, "alpha");
  EXPECT_EQ(s.ckt_snapshots().latest("bravo")->id, b1);
  EXPECT_FALSE(s.ckt_snapshots().latest("charlie").has_value());
  EXPECT_EQ(s.ckt_snapshots().latest_id("charlie"), 0);
  const auto a2 = s.ckt_snapshots().save(a, {});
  EXPECT_EQ(s.ckt_snapshots().latest("alpha")->id, a2);
  EXPECT_EQ(s.ckt_snapshots().latest_id("alpha"), a2);
  EXPECT_EQ(s.ckt_snapshots().latest_id("bravo"), b1);
  EXPECT_EQ(s.ckt_snapshots().latest("bravo")->id, b1);
}
