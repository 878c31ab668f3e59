// Schema 2: the mission runner's queries (runner pid, ConditionSet episodes, event log, mission
// clock, per-cell statistics) and the packed normalised turns the CKT is built from.

#include <gtest/gtest.h>

#include "support/schema_downgrade.hpp"
#include "support/temp_db.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_json.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using avk::testing::TempDb;
using namespace avk::store;

namespace {

std::int64_t make_mission(Store& s, const std::string& vehicle = "usim-1") {
  s.vehicles().upsert({vehicle, "usim", 2.0, 1.2});
  return s.missions().create(vehicle, "collection", "{}");
}

TurnSequence arc(double speed_mps, double dheading_deg, unsigned seed = 1,
                 const std::string& vehicle = "usim-1") {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = speed_mps;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.position_noise_m = 0.05;
  spec.heading_noise_deg = 0.5;
  spec.start = {12.5, -3.25, 33.0 + seed};
  spec.vehicle_id = vehicle;
  return avk::testing::make_arc_turn(spec);
}

// Noise-free 90-degree turn from the origin heading north: advance = lead-in + R, transfer = R.
TurnSequence exact_arc(double speed_mps, double dheading_deg, double radius_m) {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = speed_mps;
  spec.dheading_deg = dheading_deg;
  spec.lead_in_m = 2.0;
  spec.radius_m = radius_m;
  spec.dt_s = 0.05;
  return avk::testing::make_arc_turn(spec);
}

std::vector<NavRow> nav_until(double t_end_s) {
  std::vector<NavRow> rows;
  for (double t = 0.0; t <= t_end_s; t += 0.5)
    rows.push_back({t, t, 0.0, 0.0, 1.0, std::nullopt, std::nullopt, "idle"});
  rows.back().t_s = t_end_s;
  return rows;
}

void expect_mean_sd(const std::optional<avk::kinematics::MeanSd>& got, double mean, double sd) {
  ASSERT_TRUE(got.has_value());
  EXPECT_NEAR(got->mean, mean, 1e-9);
  EXPECT_NEAR(got->sd, sd, 1e-9);
}

}  // namespace

TEST(MissionQueries, SchemaIsVersionTwelve) {
  Store s(":memory:");
  EXPECT_EQ(schema_version(), 12);
  EXPECT_EQ(s.user_version(), 12);
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
  EXPECT_THROW(migration_step_sql(12), std::out_of_range);
  EXPECT_THROW(migration_step_sql(-1), std::out_of_range);
}

TEST(MissionQueries, RunnerPidSetClearedAndListed) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_FALSE(s.missions().get(m)->runner_pid);
  s.missions().set_runner(m, 4242);
  EXPECT_EQ(s.missions().get(m)->runner_pid, 4242);
  EXPECT_FALSE(s.missions().get(other)->runner_pid);
  const auto all = s.missions().list();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].runner_pid, 4242);
  EXPECT_FALSE(all[1].runner_pid);
  // Status changes leave the pid alone; only the runner clears it.
  s.missions().set_status(m, MissionStatus::running, "", 1.0);
  EXPECT_EQ(s.missions().get(m)->runner_pid, 4242);
  s.missions().set_runner(m, std::nullopt);
  EXPECT_FALSE(s.missions().get(m)->runner_pid);
  EXPECT_THROW(s.missions().set_runner(other + 10, 1), StoreError);
}

TEST(MissionQueries, ConditionSetsOrderedByStartPerMission) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_TRUE(s.missions().condition_sets(m).empty());
  s.missions().append_condition_set(m, {30.0, 41.5, 1.5, "timeout"});
  s.missions().append_condition_set(m, {10.0, 12.25, 1.0, "set"});
  s.missions().append_condition_set(other, {5.0, 6.0, 0.5, "set"});
  s.missions().append_condition_set(m, {20.0, 20.5, 1.0, "interrupted"});
  const auto got = s.missions().condition_sets(m);
  const std::vector<ConditionSetTiming> expected = {
      {10.0, 12.25, 1.0, "set"}, {20.0, 20.5, 1.0, "interrupted"}, {30.0, 41.5, 1.5, "timeout"}};
  EXPECT_EQ(got, expected);
  EXPECT_DOUBLE_EQ(got[0].duration_s(), 2.25);
  EXPECT_EQ(s.missions().condition_sets(other).size(), 1u);
  EXPECT_TRUE(s.missions().condition_sets(other + 10).empty());
}

TEST(MissionQueries, ConditionSetRejectsBadRows) {
  Store s(":memory:");
  const auto m = make_mission(s);
  EXPECT_THROW(s.missions().append_condition_set(m, {1.0, 2.0, 1.0, "done"}), StoreError);
  EXPECT_THROW(s.missions().append_condition_set(m, {2.0, 1.0, 1.0, "set"}),
               StoreError);  // ends first
  EXPECT_THROW(s.missions().append_condition_set(
                   m, {std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0, "set"}),
               StoreError);
  EXPECT_TRUE(s.missions().condition_sets(m).empty());
}

TEST(MissionQueries, ForeignKeysRejectRowsOfMissingMissions) {
  Store s(":memory:");
  const auto m = make_mission(s);
  EXPECT_THROW(s.missions().append_condition_set(m + 1, {1.0, 2.0, 1.0, "set"}), StoreError);
  EXPECT_THROW(s.missions().append_event(m + 1, 1.0, "halt", "operator"), StoreError);
  EXPECT_TRUE(s.missions().condition_sets(m + 1).empty());
  EXPECT_TRUE(s.missions().events(m + 1).empty());
  EXPECT_FALSE(s.missions().clock_end_s(m + 1));
  EXPECT_TRUE(s.integrity_check());
}

TEST(MissionQueries, EventsKeysetPaginationOldestFirst) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_TRUE(s.missions().events(m).empty());
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 25; ++i) {
    ids.push_back(s.missions().append_event(m, 0.5 * i, i % 2 ? "pause" : "containment",
                                            "event " + std::to_string(i)));
    s.missions().append_event(other, 100.0 + i, "halt", "elsewhere");
  }
  const auto all = s.missions().events(m);
  ASSERT_EQ(all.size(), 25u);
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].id, ids[i]);
    EXPECT_EQ(all[i].mission_id, m);
    EXPECT_EQ(all[i].t_s, 0.5 * static_cast<double>(i));
    EXPECT_EQ(all[i].message, "event " + std::to_string(i));
  }
  EXPECT_EQ(all[1].kind, "pause");
  EXPECT_EQ(all[2].kind, "containment");

  std::vector<std::int64_t> seen;
  std::int64_t after = 0;
  int pages = 0;
  for (;;) {
    const auto page = s.missions().events(m, after, 10);
    if (page.empty()) break;
    ++pages;
    EXPECT_LE(page.size(), 10u);
    for (const auto& e : page)
      seen.push_back(e.id);
    after = page.back().id;
  }
  EXPECT_EQ(pages, 3);
  EXPECT_EQ(seen, ids);
  EXPECT_TRUE(s.missions().events(m, ids.back()).empty());
  EXPECT_EQ(s.missions().events(other).size(), 25u);
  EXPECT_TRUE(s.missions().events(other + 10).empty());
}

TEST(MissionQueries, NavPageCoversEveryRowOnceInInsertionOrder) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_TRUE(s.navigation().page(m, 0, 10).empty());
  // Interleaved batches of two missions, and a batch stamped earlier than the one before it: the
  // pages follow insertion order, skip the other mission and never repeat or lose a row.
  std::vector<NavRow> expected;
  for (int batch = 0; batch < 5; ++batch) {
    auto rows = nav_until(10.0);
    for (auto& r : rows) {
      r.t_s += batch == 3 ? -100.0 : 20.0 * batch;
      r.x_m = static_cast<double>(expected.size() + (&r - rows.data()));
      r.desired_heading_deg = batch % 2 ? std::optional<double>(45.0 + batch) : std::nullopt;
      r.helm_mode = batch % 2 ? "TURNING" : "idle";
    }
    s.navigation().append(m, rows);
    expected.insert(expected.end(), rows.begin(), rows.end());
    s.navigation().append(other, nav_until(3.0));
  }
  ASSERT_EQ(expected.size(), 105u);
  std::vector<NavRow> seen;
  std::int64_t after = 0;
  int pages = 0;
  for (;;) {
    const auto page = s.navigation().page(m, after, 20);
    if (page.empty()) break;
    ++pages;
    EXPECT_LE(page.size(), 20u);
    for (const auto& r : page) {
      EXPECT_GT(r.rowid, after);
      after = r.rowid;
      seen.push_back(r.row);
    }
  }
  EXPECT_EQ(pages, 6);
  EXPECT_EQ(seen, expected);
  EXPECT_TRUE(s.navigation().page(m, after, 20).empty());
  EXPECT_EQ(s.navigation().page(other, 0, 1000).size(), 5u * nav_until(3.0).size());
  EXPECT_TRUE(s.navigation().page(other + 10, 0, 1000).empty());
}

TEST(MissionQueries, ClockEndIsTheLatestOfEverySource) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_FALSE(s.missions().clock_end_s(m));
  EXPECT_FALSE(s.missions().clock_end_s(other + 10));
  // Status times are not records of the mission's work.
  s.missions().set_status(m, MissionStatus::running, "", 0.5);
  EXPECT_FALSE(s.missions().clock_end_s(m));

  // Each source in turn holds the latest time, so a source the query forgot would show.
  s.navigation().append(m, nav_until(2.0));
  EXPECT_EQ(s.missions().clock_end_s(m), 2.0);
  s.missions().append_condition_set(m, {2.5, 3.0, 1.0, "set"});
  EXPECT_EQ(s.missions().clock_end_s(m), 3.0);
  TurnSequence turn = arc(1.0, 90.0);
  ASSERT_GT(turn.meta().end_time_s, 3.0);
  s.turns().add(m, turn, TurnStatus::aborted, "halt");
  EXPECT_EQ(s.missions().clock_end_s(m), turn.meta().end_time_s);
  s.missions().append_event(m, 40.0, "halt", "operator");
  EXPECT_EQ(s.missions().clock_end_s(m), 40.0);
  s.navigation().append(m, nav_until(55.0));
  EXPECT_EQ(s.missions().clock_end_s(m), 55.0);
  s.missions().append_condition_set(m, {56.0, 60.0, 1.0, "timeout"});
  EXPECT_EQ(s.missions().clock_end_s(m), 60.0);

  // Another mission's records never move this one's clock.
  s.navigation().append(other, nav_until(500.0));
  s.missions().append_event(other, 600.0, "pause", "");
  EXPECT_EQ(s.missions().clock_end_s(m), 60.0);
  EXPECT_EQ(s.missions().clock_end_s(other), 600.0);
}

TEST(MissionQueries, CellStatsMatchHandComputedValues) {
  Store s(":memory:");
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_TRUE(s.missions().cell_stats(m).empty());
  EXPECT_TRUE(s.missions().cell_stats(other + 10).empty());

  // Cell (1.0, 90): ok turns with R = 2, 3, 5 (lead-in 2), right and left.
  s.turns().add(m, exact_arc(1.0, 90.0, 2.0), TurnStatus::ok, "", {2.0, {}, {}});
  s.turns().add(m, exact_arc(1.0, -90.0, 3.0), TurnStatus::ok, "", {4.0, {}, {}});
  s.turns().add(m, exact_arc(1.0, 90.0, 5.0), TurnStatus::ok, "");
  // Not ok turns count but never enter the means; neither does another mission.
  s.turns().add(m, exact_arc(1.0, -90.0, 50.0), TurnStatus::aborted, "containment",
                {100.0, {}, {}});
  s.turns().add(other, exact_arc(1.0, 90.0, 50.0), TurnStatus::ok, "", {100.0, {}, {}});
  // Cell (1.0, 40): rejected only.
  s.turns().add(m, exact_arc(1.0, 40.0, 3.0), TurnStatus::rejected, "noisy", {1.0, {}, {}});
  // Cell (0.5, 90): one ok turn, without a ConditionSet time.
  s.turns().add(m, exact_arc(0.5, 90.0, 3.0), TurnStatus::ok, "");

  const auto cells = s.missions().cell_stats(m);
  ASSERT_EQ(cells.size(), 3u);

  EXPECT_EQ(cells[0].speed_mps, 0.5);
  EXPECT_EQ(cells[0].dheading_deg, 90.0);
  EXPECT_EQ(cells[0].n_ok, 1);
  EXPECT_EQ(cells[0].n_aborted, 0);
  EXPECT_EQ(cells[0].n_rejected, 0);
  expect_mean_sd(cells[0].advance_m, 5.0, 0.0);
  expect_mean_sd(cells[0].transfer_m, 3.0, 0.0);
  EXPECT_FALSE(cells[0].condition_set_time_s);

  EXPECT_EQ(cells[1].speed_mps, 1.0);
  EXPECT_EQ(cells[1].dheading_deg, 40.0);
  EXPECT_EQ(cells[1].n_ok, 0);
  EXPECT_EQ(cells[1].n_rejected, 1);
  EXPECT_FALSE(cells[1].advance_m);
  EXPECT_FALSE(cells[1].transfer_m);
  EXPECT_FALSE(cells[1].condition_set_time_s);

  EXPECT_EQ(cells[2].speed_mps, 1.0);
  EXPECT_EQ(cells[2].dheading_deg, 90.0);
  EXPECT_EQ(cells[2].n_ok, 3);
  EXPECT_EQ(cells[2].n_aborted, 1);
  EXPECT_EQ(cells[2].n_rejected, 0);
  // Advances 4, 5, 7: mean 16/3, deviations -4/3, -1/3, 5/3, sd sqrt((16 + 1 + 25) / 9 / 2).
  expect_mean_sd(cells[2].advance_m, 16.0 / 3.0, std::sqrt(7.0 / 3.0));
  // Transfers 2, 3, 5: mean 10/3, the same deviations.
  expect_mean_sd(cells[2].transfer_m, 10.0 / 3.0, std::sqrt(7.0 / 3.0));
  // Only the two ok turns with a time: 2 and 4.
  expect_mean_sd(cells[2].condition_set_time_s, 3.0, std::sqrt(2.0));

  const auto theirs = s.missions().cell_stats(other);
  ASSERT_EQ(theirs.size(), 1u);
  EXPECT_EQ(theirs[0].n_ok, 1);
  expect_mean_sd(theirs[0].advance_m, 52.0, 0.0);
}

TEST(MissionQueries, LoadNormalizedTurnsEqualsGetTurn) {
  Store s(":memory:");
  const auto m1 = make_mission(s, "usim-1");
  const auto m2 = make_mission(s, "usim-2");
  TurnSequence warned = arc(1.5, -160.0, 4);
  warned.add_warning("NAV_X stream cut by 1 value");
  TurnSequence pre_normalized = arc(0.5, 70.0, 5).normalized();
  std::vector<std::int64_t> ok_m1, ok_m2;
  ok_m1.push_back(s.turns().add(m1, arc(1.0, 90.0, 1), TurnStatus::ok, "", {3.0, {}, {}}));
  ok_m1.push_back(s.turns().add(m1, arc(1.0, -40.0, 2), TurnStatus::ok, "kept despite drift"));
  s.turns().add(m1, arc(1.0, 90.0, 3), TurnStatus::aborted, "halt");
  ok_m1.push_back(s.turns().add(m1, warned, TurnStatus::ok, ""));
  ok_m2.push_back(s.turns().add(m2, arc(0.5, 10.0, 6, "usim-2"), TurnStatus::ok, ""));
  s.turns().add(m2, arc(0.5, 10.0, 7, "usim-2"), TurnStatus::rejected, "noisy");
  ok_m1.push_back(s.turns().add(m1, pre_normalized, TurnStatus::ok, ""));
  // The turn's own vehicle, not the mission's, is what the vehicle filter matches.
  ok_m2.push_back(s.turns().add(m2, arc(1.5, 130.0, 8, "usim-1"), TurnStatus::ok, ""));

  const auto expect_turns = [&](const std::vector<TurnSequence>& got,
                                const std::vector<std::int64_t>& ids) {
    ASSERT_EQ(got.size(), ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const auto stored = s.turns().get(ids[i]);
      ASSERT_TRUE(stored && stored->normalized);
      EXPECT_EQ(got[i], *stored->normalized) << "turn " << ids[i];
      EXPECT_EQ(got[i].warnings(), stored->normalized->warnings()) << "turn " << ids[i];
      EXPECT_EQ(avk::kinematics::to_json_string(got[i]),
                avk::kinematics::to_json_string(*stored->normalized));
    }
  };
  const std::vector<std::int64_t> all = {ok_m1[0], ok_m1[1], ok_m1[2],
                                         ok_m2[0], ok_m1[3], ok_m2[1]};
  expect_turns(s.turns().load_normalized({}), all);
  expect_turns(s.turns().load_normalized({m1, m2}), all);
  expect_turns(s.turns().load_normalized({m2, m1, m1}), all);
  expect_turns(s.turns().load_normalized({m1}), ok_m1);
  expect_turns(s.turns().load_normalized({m2}), ok_m2);
  expect_turns(s.turns().load_normalized({}, "usim-2"), {ok_m2[0]});
  expect_turns(s.turns().load_normalized({}, "usim-1"),
               {ok_m1[0], ok_m1[1], ok_m1[2], ok_m1[3], ok_m2[1]});
  expect_turns(s.turns().load_normalized({m2}, "usim-1"), {ok_m2[1]});
  EXPECT_TRUE(s.turns().load_normalized({m1}, "usim-2").empty());
  EXPECT_TRUE(s.turns().load_normalized({}, "ghost").empty());
  EXPECT_TRUE(s.turns().load_normalized({m2 + 10}).empty());
  // Left out: one mission's turns, one turn, or both; with or without a mission list.
  TurnsLeftOut no_m1;
  no_m1.mission_id = m1;
  expect_turns(s.turns().load_normalized({}, std::nullopt, false, TurnFrameChoice::ground, no_m1),
               ok_m2);
  expect_turns(s.turns().load_normalized({m1}, std::nullopt, false, TurnFrameChoice::ground, no_m1),
               {});
  TurnsLeftOut no_turn;
  no_turn.turn_id = ok_m1[1];
  expect_turns(s.turns().load_normalized({m1}, "usim-1", false, TurnFrameChoice::ground, no_turn),
               {ok_m1[0], ok_m1[2], ok_m1[3]});
  no_turn.mission_id = m2;
  expect_turns(s.turns().load_normalized({}, std::nullopt, false, TurnFrameChoice::ground, no_turn),
               {ok_m1[0], ok_m1[2], ok_m1[3]});
  // A turn's row alone equals the row turns().get reads with its documents.
  const auto row = s.turns().get_row(ok_m2[1]);
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->mission_id, m2);
  EXPECT_EQ(row->vehicle_id, "usim-1");
  EXPECT_EQ(row->goal_dheading_deg, s.turns().get(ok_m2[1])->row.goal_dheading_deg);
  EXPECT_FALSE(s.turns().get_row(ok_m2[1] + 100).has_value());

  const auto loaded = s.turns().load_normalized({m1});
  EXPECT_EQ(loaded[0], arc(1.0, 90.0, 1).normalized());
  EXPECT_EQ(loaded[3], pre_normalized);
  EXPECT_EQ(loaded[1].meta().status_reason, "kept despite drift");
  for (const auto& t : loaded) {
    EXPECT_TRUE(t.meta().normalized);
    EXPECT_EQ(t.meta().status, TurnStatus::ok);
  }
}

TEST(MissionQueries, LoadNormalizedTurnsEmptyDatabase) {
  Store s(":memory:");
  EXPECT_TRUE(s.turns().load_normalized({}).empty());
  EXPECT_TRUE(s.turns().load_normalized({1, 2}).empty());
  EXPECT_TRUE(s.turns().load_normalized({}, "usim-1").empty());
}

TEST(MissionQueries, NormalizedSamplesArePackedLittleEndianFloat64) {
  TempDb db;
  std::int64_t id = 0;
  TurnSequence norm;
  {
    Store s(db.path());
    const auto m = make_mission(s);
    id = s.turns().add(m, arc(1.0, -70.0, 9), TurnStatus::ok, "");
    norm = *s.turns().get(id)->normalized;
  }
  {
    Connection c(db.path());
    auto q = c.prepare("SELECT normalized_samples FROM turns WHERE id = ?");
    q.bind(1, id);
    ASSERT_TRUE(q.step());
    const auto blob = q.column_blob(0);
    ASSERT_EQ(blob.size(), norm.samples().size() * 5 * 8);
    const auto value = [&](std::size_t k) {
      std::uint64_t bits = 0;
      for (std::size_t b = 0; b < 8; ++b)
        bits |= static_cast<std::uint64_t>(blob[8 * k + b]) << (8 * b);
      return std::bit_cast<double>(bits);
    };
    for (std::size_t i = 0; i < norm.samples().size(); ++i) {
      const auto& p = norm.samples()[i];
      EXPECT_EQ(value(5 * i + 0), p.t_s);
      EXPECT_EQ(value(5 * i + 1), p.x_m);
      EXPECT_EQ(value(5 * i + 2), p.y_m);
      EXPECT_EQ(value(5 * i + 3), p.heading_deg);
      EXPECT_EQ(value(5 * i + 4), p.speed_mps);
    }
    // With the JSON document broken, only the packed path can still produce the turn.
    c.exec("UPDATE turns SET normalized_json = '{'");
  }
  Store s(db.path());
  const auto loaded = s.turns().load_normalized({});
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0], norm);
  EXPECT_THROW(s.turns().get(id), StoreError);
}

TEST(MissionQueries, CorruptPackedSamplesNameTheTurn) {
  TempDb db;
  std::int64_t id = 0;
  {
    Store s(db.path());
    id = s.turns().add(make_mission(s), arc(1.0, 90.0), TurnStatus::ok, "");
  }
  {
    Connection c(db.path());
    c.exec("UPDATE turns SET normalized_samples = x'00010203'");
  }
  Store s(db.path());
  try {
    s.turns().load_normalized({});
    FAIL() << "a truncated sample blob was read";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("turn " + std::to_string(id)), std::string::npos)
        << e.what();
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

TEST(MissionQueries, YawModelsRoundTripAndAreFoundByVehicle) {
  Store s(":memory:");
  EXPECT_FALSE(s.models().latest().has_value());
  StoredModel m;
  m.vehicle_id = "cat-1";
  m.training_missions = {3, 5};
  m.model.form = avk::kinematics::YawModelForm::thesis;
  m.model.history = 2;
  m.model.error_coeffs = {0.25, -0.125};
  m.model.heading_coeffs = {1.5, -0.5};
  m.model.ridge_lambda = 1e-4;
  m.model.refined = true;
  m.model.speed = avk::kinematics::SpeedModel{0.2, 0.01, -0.001};
  m.train_one_step_rms_deg = 1.25;
  m.validation_mse_m2 = 2.5;
  const auto a = s.models().save(m);
  m.vehicle_id = "usim-1";
  m.validation_mse_m2.reset();
  const auto b = s.models().save(m);
  const auto got = s.models().get(a);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->vehicle_id, "cat-1");
  EXPECT_EQ(got->training_missions, (std::vector<std::int64_t>{3, 5}));
  EXPECT_EQ(got->model.error_coeffs, m.model.error_coeffs);
  EXPECT_EQ(got->model.heading_coeffs, m.model.heading_coeffs);
  EXPECT_EQ(got->model.form, avk::kinematics::YawModelForm::thesis);
  EXPECT_TRUE(got->model.refined);
  ASSERT_TRUE(got->model.speed.has_value());
  EXPECT_DOUBLE_EQ(got->model.speed->sag_per_deg, 0.01);
  EXPECT_EQ(got->validation_mse_m2, std::optional<double>(2.5));
  EXPECT_FALSE(s.models().get(b)->validation_mse_m2.has_value());
  EXPECT_FALSE(s.models().get(99).has_value());
  EXPECT_EQ(s.models().latest()->id, b);
  EXPECT_EQ(s.models().latest(std::string("cat-1"))->id, a);
  EXPECT_FALSE(s.models().latest(std::string("otter")).has_value());
  EXPECT_EQ(s.models().list().size(), 2u);
  EXPECT_EQ(s.models().list(std::string("usim-1")).size(), 1u);
}

TEST(MissionQueries, NewestOkTurnIdPerVehicle) {
  Store s(":memory:");
  EXPECT_EQ(s.turns().newest_ok_id("usim-1"), 0);
  const auto m = make_mission(s);
  const auto a = s.turns().add(m, arc(1.0, 40.0, 1), TurnStatus::ok, "");
  s.turns().add(m, arc(1.0, 40.0, 2), TurnStatus::aborted, "containment");
  EXPECT_EQ(s.turns().newest_ok_id("usim-1"), a);
  EXPECT_EQ(s.turns().newest_ok_id("other"), 0);
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

// When a mission ran, in wall-clock time, kept with it: its first start (a resume keeps
// it) and its end, so a mission of an earlier server session still says when it ran.
TEST(MissionQueries, AMissionKeepsTheWallClockMomentsItStartedAndEnded) {
  Store s(":memory:");
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.0});
  const auto m = s.missions().create("usim-1", "clock", "{}");
  EXPECT_FALSE(s.missions().get(m)->started_utc);
  s.missions().set_status(m, MissionStatus::running, "", 100.0);
  const auto started = s.missions().get(m)->started_utc;
  ASSERT_TRUE(started);
  EXPECT_TRUE(std::regex_match(*started, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << *started;
  EXPECT_GE(*started, s.missions().get(m)->created_utc);  // ISO 8601 orders as text
  // A stop (SIGTERM, `docker stop`) ends the run with its time, so the elapsed time of the
  // interrupted mission is known; a resume runs it again, without an end.
  s.missions().set_status(m, MissionStatus::interrupted, "the server stopped", 150.0);
  const auto interrupted = s.missions().get(m);
  EXPECT_EQ(interrupted->ended_s, 150.0);
  ASSERT_TRUE(interrupted->ended_utc);
  EXPECT_GE(*interrupted->ended_utc, *started);
  s.missions().set_status(m, MissionStatus::running, "", 400.0);  // resumed in a later session
  EXPECT_EQ(s.missions().get(m)->started_utc, started);
  EXPECT_EQ(s.missions().get(m)->started_s, 100.0);
  EXPECT_FALSE(s.missions().get(m)->ended_s);
  EXPECT_FALSE(s.missions().get(m)->ended_utc);
  s.missions().set_status(m, MissionStatus::done, "", 500.0);
  const auto done = s.missions().get(m);
  ASSERT_TRUE(done->ended_utc);
  EXPECT_GE(*done->ended_utc, *started);
}

// A mission whose process was killed (kill -9) stored no end: closing it stores the end it is
// given, clears the runner and leaves the wall-clock end unknown rather than making one up.
TEST(MissionQueries, AnOrphanedMissionIsClosedAsInterruptedAtTheEndGiven) {
  Store s(":memory:");
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.0});
  const auto m = s.missions().create("usim-1", "killed", "{}");
  s.missions().set_status(m, MissionStatus::running, "", 100.0);
  s.missions().set_runner(m, 4242);
  s.missions().close_orphaned(m, "the process running it stopped", 187.5);
  const auto closed = s.missions().get(m);
  EXPECT_EQ(closed->status, MissionStatus::interrupted);
  EXPECT_EQ(closed->status_reason, "the process running it stopped");
  EXPECT_EQ(closed->started_s, 100.0);
  EXPECT_EQ(closed->ended_s, 187.5);
  EXPECT_FALSE(closed->ended_utc);
  EXPECT_FALSE(closed->runner_pid);
  EXPECT_THROW(s.missions().close_orphaned(m + 10, "x", 1.0), StoreError);
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
