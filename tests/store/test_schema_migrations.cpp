// The store's schema version and its upgrades of older files: schema 1, 8 (speed after a turn)
// and 10 (missions without wall-clock times), each keeping what the file held.
#include <gtest/gtest.h>

#include "store/mission_rows.hpp"

using namespace avk::testing::mission_rows;

TEST(MissionQueries, SchemaIsVersionThirteen) {
  Store s(":memory:");
  EXPECT_EQ(schema_version(), 13);
  EXPECT_EQ(s.user_version(), 13);
  EXPECT_FALSE(migration_step_sql(0).empty());
  EXPECT_NE(migration_step_sql(1).find("normalized_samples"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(2).find("yaw_models"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(3).find("turns_by_vehicle_status"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(4).find("nav_by_mission"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(5).find("ckt_snapshots_by_vehicle"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(6).find("start_heading_error_deg"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(7).find("harvests"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(8).find("speed_after_mps"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(9).find("mission_currents"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(10).find("started_utc"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(11).find("speed_reference"), std::string_view::npos);
  EXPECT_NE(migration_step_sql(12).find("record_key"), std::string_view::npos);
  EXPECT_THROW(migration_step_sql(13), std::out_of_range);
  EXPECT_THROW(migration_step_sql(-1), std::out_of_range);
}

// Both engines run the same numbered steps, each in its own dialect: the step that adds a table
// or a column adds it on both.
TEST(MissionQueries, BothEnginesHaveEveryStepInTheirOwnDialect) {
  for (int i = 0; i < schema_version(); ++i) {
    const auto lite = migration_step_sql(i, Engine::sqlite);
    const auto pg = migration_step_sql(i, Engine::postgresql);
    EXPECT_FALSE(pg.empty()) << "step " << i + 1;
    for (const char* word : {"CREATE TABLE ", "ADD COLUMN ", "CREATE INDEX ", "CREATE UNIQUE"}) {
      std::size_t n_lite = 0, n_pg = 0;
      for (auto at = lite.find(word); at != std::string_view::npos; at = lite.find(word, at + 1))
        ++n_lite;
      for (auto at = pg.find(word); at != std::string_view::npos; at = pg.find(word, at + 1))
        ++n_pg;
      EXPECT_EQ(n_lite, n_pg) << "step " << i + 1 << ": " << word;
    }
    // PostgreSQL's REAL is four bytes; every double is DOUBLE PRECISION there.
    EXPECT_EQ(pg.find(" REAL"), std::string_view::npos) << "step " << i + 1;
  }
}

// A file exactly as schema 1 left it: the released step 1, rows written the way the version 1
// store wrote them (no packed samples, no runner pid, no events or ConditionSet tables).
TEST(MissionQueries, MigratesSchemaOneDatabase) {
  TempDb db;
  const TurnSequence ok_turn = arc(1.0, -100.0, 11);
  const TurnSequence aborted_turn = arc(1.5, 40.0, 12);
  {
    Connection c(db.path());
    c.exec("PRAGMA foreign_keys = ON");
    c.exec(std::string(migration_step_sql(0)).c_str());
    c.exec("PRAGMA user_version = 1");
    c.exec(
        "INSERT INTO vehicles (id, kind, max_speed_mps, length_m) VALUES ('usim-1', 'usim', 2, 1)");
    c.exec(
        "INSERT INTO missions (id, vehicle_id, name, config_json, status, started_s) "
        "VALUES (7, 'usim-1', 'old', '{}', 'interrupted', 1.0)");
    auto ins = c.prepare(
        "INSERT INTO turns (mission_id, vehicle_id, cell_speed_mps, cell_dheading_deg, status, "
        "reason, commanded_speed_mps, goal_dheading_deg, observed_dheading_deg, start_time_s, "
        "end_time_s, advance_m, transfer_m, condition_set_time_s, raw_json, normalized_json) "
        "VALUES (7, 'usim-1', ?, ?, ?, ?, ?, ?, ?, ?, ?, 1.0, 1.0, 2.5, ?, ?)");
    for (const auto* t : {&ok_turn, &aborted_turn}) {
      const bool ok = t == &ok_turn;
      TurnSequence raw = *t;
      raw.meta().status = ok ? TurnStatus::ok : TurnStatus::aborted;
      raw.meta().status_reason = ok ? "" : "halt";
      const auto& m = raw.meta();
      ins.bind(1, m.commanded_speed_mps).bind(2, std::abs(m.goal_dheading_deg));
      ins.bind(3, ok ? "ok" : "aborted").bind(4, m.status_reason);
      ins.bind(5, m.commanded_speed_mps).bind(6, m.goal_dheading_deg);
      ins.bind(7, m.observed_dheading_deg).bind(8, m.start_time_s).bind(9, m.end_time_s);
      ins.bind(10, avk::kinematics::to_json_string(raw));
      ins.bind(11, avk::kinematics::to_json_string(raw.normalized()));
      ins.run();
      ins.reset();
    }
    // A table imported before snapshots knew their vehicle: the migration reads it from the file.
    avk::kinematics::Ckt table = avk::kinematics::Ckt::build({ok_turn});
    table.vehicle_id = "usim-1";
    c.prepare("INSERT INTO ckt_snapshots (id, mission_ids, document) VALUES (3, '[7]', ?)")
        .bind(1, avk::kinematics::ckt_to_json_string(table))
        .run();
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  ASSERT_TRUE(s.ckt_snapshots().latest("usim-1"));
  EXPECT_EQ(s.ckt_snapshots().latest("usim-1")->id, 3);
  EXPECT_FALSE(s.ckt_snapshots().latest("other"));
  EXPECT_TRUE(s.integrity_check());
  const auto mission = s.missions().get(7);
  ASSERT_TRUE(mission);
  EXPECT_EQ(mission->name, "old");
  EXPECT_FALSE(mission->runner_pid);

  const auto rows = s.turns().list({});
  ASSERT_EQ(rows.size(), 2u);
  const auto old = s.turns().get(rows[0].id);
  ASSERT_TRUE(old && old->normalized);
  EXPECT_EQ(old->raw, ok_turn);
  EXPECT_EQ(*old->normalized, ok_turn.normalized());

  // The old row has no packed samples: it loads through its JSON; a new one through the blob.
  auto loaded = s.turns().load_normalized({7});
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0], *old->normalized);
  const auto fresh = s.turns().add(7, arc(0.5, 10.0, 13), TurnStatus::ok, "");
  loaded = s.turns().load_normalized({});
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded[0], *old->normalized);
  EXPECT_EQ(loaded[1], *s.turns().get(fresh)->normalized);

  // The new tables and column work on the migrated file.
  s.missions().set_runner(7, 99);
  EXPECT_EQ(s.missions().get(7)->runner_pid, 99);
  s.missions().append_event(7, 2.0, "pause", "resumed later");
  s.missions().append_condition_set(7, {1.0, 1.5, 1.0, "set"});
  EXPECT_EQ(s.missions().events(7).size(), 1u);
  EXPECT_EQ(s.missions().condition_sets(7).size(), 1u);
  EXPECT_EQ(s.missions().clock_end_s(7),
            std::max({ok_turn.meta().end_time_s, aborted_turn.meta().end_time_s,
                      s.turns().get(fresh)->row.end_time_s}));
  const auto cells = s.missions().cell_stats(7);
  ASSERT_EQ(cells.size(), 3u);
  // The per-mission totals of one query agree with the cells.
  const auto counts = s.missions().turn_counts();
  ASSERT_EQ(counts.size(), 1u);
  EXPECT_EQ(counts.at(7), (avk::store::TurnCounts{2, 1, 0}));
  EXPECT_EQ(cells[2].n_aborted, 1);
  EXPECT_EQ(cells[1].n_ok, 1);
  expect_mean_sd(cells[1].condition_set_time_s, 2.5, 0.0);
  EXPECT_TRUE(s.integrity_check());
}

// A database at schema 7 (before speed_after_mps) upgrades, keeps its turns (with
// no speed after), and then stores and reads back a speed-change turn and its cell.
TEST(MissionQueries, MigratesSchemaEightDatabaseToSpeedAfter) {
  TempDb db;
  const TurnSequence old_turn = arc(1.0, 90.0, 21);
  {
    Store s(db.path());
    s.vehicles().upsert({"usim-1", "usim", 2.0, 1.0});
    const auto m = s.missions().create("usim-1", "old", "{}");
    s.turns().add(m, old_turn, TurnStatus::ok, "");
  }
  {
    // Back to schema 8, as a station before this step (and the currents after it) left it.
    Connection c(db.path());
    avk::testing::downgrade_schema(c, 8);
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  const auto rows = s.turns().list({});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_FALSE(rows[0].speed_after_mps);
  EXPECT_EQ(s.turns().get(rows[0].id)->raw, old_turn);
  TurnSequence slowing = arc(1.5, 90.0, 22);
  slowing.meta().speed_after_mps = 0.75;
  const auto id = s.turns().add(rows[0].mission_id, slowing, TurnStatus::ok, "");
  const auto stored = s.turns().get(id);
  ASSERT_TRUE(stored);
  EXPECT_EQ(stored->row.speed_after_mps, 0.75);
  EXPECT_EQ(stored->raw.meta().speed_after_mps, 0.75);
  const auto loaded = s.turns().load_normalized({rows[0].mission_id});
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded[1].meta().speed_after_mps, 0.75);
  // A speed-change cell is its own, even at a constant-speed cell's speed and heading change.
  s.turns().add(rows[0].mission_id, arc(1.5, 90.0, 23), TurnStatus::ok, "");
  const auto cells = s.missions().cell_stats(rows[0].mission_id);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_FALSE(cells[1].speed_after_mps);
  EXPECT_EQ(cells[2].speed_after_mps, 0.75);
  EXPECT_EQ(cells[2].n_ok, 1);
  EXPECT_TRUE(s.integrity_check());
}

// A schema-10 file: its missions keep everything and have no wall-clock start or end.
TEST(MissionQueries, ASchemaTenDatabaseUpgradesAndItsMissionsHaveNoWallClockTimes) {
  TempDb db;
  std::int64_t m = 0;
  {
    Store s(db.path());
    s.vehicles().upsert({"usim-1", "usim", 2.0, 1.0});
    m = s.missions().create("usim-1", "old", "{}");
  }
  {
    Connection c(db.path());
    avk::testing::downgrade_schema(c, 10);
    c.exec("UPDATE missions SET status = 'done', started_s = 10, ended_s = 20");
  }
  Store s(db.path());
  EXPECT_EQ(s.user_version(), schema_version());
  const auto old = s.missions().get(m);
  ASSERT_TRUE(old);
  EXPECT_EQ(old->name, "old");
  EXPECT_EQ(old->started_s, 10.0);
  EXPECT_FALSE(old->started_utc);
  EXPECT_FALSE(old->ended_utc);
}
