// The store's queries for the mission runner: runner pid, ConditionSet episodes, the event log,
// nav pages, the mission clock, per-cell statistics, and a mission's wall-clock start and end.
#include <gtest/gtest.h>

#include "support/store_engines.hpp"

#include "store/mission_rows.hpp"

using namespace avk::testing::mission_rows;

namespace {

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

}  // namespace

class MissionQueriesOnEngine : public avk::testing::OnEachEngine {};
AVK_ON_EACH_ENGINE(MissionQueriesOnEngine);

TEST_P(MissionQueriesOnEngine, RunnerPidSetClearedAndListed) {
  Store s(db());
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

TEST_P(MissionQueriesOnEngine, ConditionSetsOrderedByStartPerMission) {
  Store s(db());
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

TEST_P(MissionQueriesOnEngine, ConditionSetRejectsBadRows) {
  Store s(db());
  const auto m = make_mission(s);
  EXPECT_THROW(s.missions().append_condition_set(m, {1.0, 2.0, 1.0, "done"}), StoreError);
  EXPECT_THROW(s.missions().append_condition_set(m, {2.0, 1.0, 1.0, "set"}),
               StoreError);  // ends first
  EXPECT_THROW(s.missions().append_condition_set(
                   m, {std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0, "set"}),
               StoreError);
  EXPECT_TRUE(s.missions().condition_sets(m).empty());
}

TEST_P(MissionQueriesOnEngine, ForeignKeysRejectRowsOfMissingMissions) {
  Store s(db());
  const auto m = make_mission(s);
  EXPECT_THROW(s.missions().append_condition_set(m + 1, {1.0, 2.0, 1.0, "set"}), StoreError);
  EXPECT_THROW(s.missions().append_event(m + 1, 1.0, "halt", "operator"), StoreError);
  EXPECT_TRUE(s.missions().condition_sets(m + 1).empty());
  EXPECT_TRUE(s.missions().events(m + 1).empty());
  EXPECT_FALSE(s.missions().clock_end_s(m + 1));
  EXPECT_TRUE(s.integrity_check());
}

TEST_P(MissionQueriesOnEngine, EventsKeysetPaginationOldestFirst) {
  Store s(db());
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

TEST_P(MissionQueriesOnEngine, NavPageCoversEveryRowOnceInInsertionOrder) {
  Store s(db());
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

TEST_P(MissionQueriesOnEngine, LastPositionIsTheLatestOnTheMissionClockNotTheLastRecorded) {
  Store s(db());
  const auto m = make_mission(s);
  const auto other = make_mission(s);
  EXPECT_FALSE(s.navigation().last(m));
  std::vector<NavRow> rows = nav_until(3.0);
  for (auto& r : rows)
    r.x_m = 10.0 * r.t_s;
  // Recorded after the others but earlier on the clock (a resumed run's replay, an import).
  NavRow early = rows.front();
  early.t_s = -5.0;
  early.x_m = -1.0;
  s.navigation().append(m, rows);
  s.navigation().append(m, std::vector<NavRow>{early});
  s.navigation().append(other, nav_until(9.0));
  const auto last = s.navigation().last(m);
  ASSERT_TRUE(last);
  EXPECT_EQ(last->row, rows.back());
  // Of two reports at one time, the one recorded last.
  NavRow again = rows.back();
  again.x_m = 99.0;
  s.navigation().append(m, std::vector<NavRow>{again});
  EXPECT_EQ(s.navigation().last(m)->row, again);
  EXPECT_GT(s.navigation().last(m)->rowid, last->rowid);
  EXPECT_FALSE(s.navigation().last(other + 10));
}

TEST_P(MissionQueriesOnEngine, ClockEndIsTheLatestOfEverySource) {
  Store s(db());
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

TEST_P(MissionQueriesOnEngine, CellStatsMatchHandComputedValues) {
  Store s(db());
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

// When a mission ran, in wall-clock time, kept with it: its first start (a resume keeps
// it) and its end, so a mission of an earlier server session still says when it ran.
TEST_P(MissionQueriesOnEngine, AMissionKeepsTheWallClockMomentsItStartedAndEnded) {
  Store s(db());
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
TEST_P(MissionQueriesOnEngine, AnOrphanedMissionIsClosedAsInterruptedAtTheEndGiven) {
  Store s(db());
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
