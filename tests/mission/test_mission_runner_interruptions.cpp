// What interrupts the mission runner's turns: a start outside the region, the buffer, too little
// room ahead, cells given up, leaving the region, the operator, link loss, conditions never set.
#include <gtest/gtest.h>

#include <algorithm>

#include "kinematics/geometry.hpp"
#include "mission/mission_sim.hpp"
#include "mission/station_keeping.hpp"

using namespace avk::testing::mission_sim;

// ---- 2. Dockside start ----------------------------------------------------------------------

TEST(MissionRunner, StartingOutsideTheRegionTransitsInsteadOfHalting) {
  Sim r(turns_config({1.0}, {90}, DirectionPolicy::right, square_region(200, 20)),
        FakeVehicle(0, -230, 180, 1.0));  // outside, heading away
  r.run_for(10);
  EXPECT_EQ(r.runner.mode(), HelmMode::transiting);
  EXPECT_EQ(r.runner.state(), MissionState::running);
  EXPECT_EQ(r.vehicle.all_stops, 0);
  ASSERT_TRUE(r.runner.desired_heading_deg());
  const double to_interior = k::heading_of_deg(-r.vehicle.x(), -r.vehicle.y());
  EXPECT_NEAR(k::angle180_deg(*r.runner.desired_heading_deg() - to_interior), 0.0, 2.0);
  EXPECT_NE(r.rec.event(EventKind::containment, "transiting to it"), nullptr);
  ASSERT_TRUE(r.until_mode(HelmMode::containing, 200));  // in the buffer
  EXPECT_GT(r.vehicle.y(), -200.0);
  ASSERT_TRUE(r.until_mode(HelmMode::conditioning, 200));
  EXPECT_GT(r.vehicle.y(), -180.0);  // conditions only in the interior
  EXPECT_EQ(r.vehicle.all_stops, 0);
  EXPECT_EQ(r.rec.event(EventKind::halted), nullptr);
  // Having been inside, leaving the region halts.
  r.run_for(0.2, [&](double) { r.vehicle.teleport(0, -230); });
  EXPECT_EQ(r.runner.state(), MissionState::halted);
  EXPECT_EQ(r.vehicle.all_stops, 1);
}

// ---- 4. Containment abort and re-queue ------------------------------------------------------

TEST(MissionRunner, TurnIntoTheBufferIsAbortedRequeuedAndRetried) {
  // Heading east 10 m from the buffer; a right turn of radius 11.5 m runs into it. The helm's
  // foresight (turning back when the run ahead is short) is off, so that the turn is tried.
  MissionConfig c = turns_config({1.0}, {90}, DirectionPolicy::right, square_region(50, 10));
  c.condition_set.run_ahead_s = 0.0;
  Sim r(c, FakeVehicle(30, 0, 90, 1.0));
  r.vehicle.yaw_rate_dps = 5.0;
  ASSERT_TRUE(r.finish());
  EXPECT_EQ(r.runner.state(), MissionState::done);
  ASSERT_GE(r.rec.turns.size(), 2u);
  const TurnOutcome& first = r.rec.turns[0];
  EXPECT_EQ(first.status, TurnStatus::aborted);
  EXPECT_EQ(first.reason.rfind("containment", 0), 0u) << first.reason;
  EXPECT_TRUE(first.requeued);
  EXPECT_FALSE(first.given_up);
  EXPECT_EQ(first.task.attempts, 1);
  EXPECT_EQ(first.raw.meta().status, TurnStatus::aborted);
  EXPECT_NE(r.rec.event(EventKind::containment, "during a turn"), nullptr);
  EXPECT_NE(r.rec.event(EventKind::turn_aborted, "re-queued"), nullptr);
  const auto it = std::find_if(r.rec.modes.begin(), r.rec.modes.end(), [](const auto& m) {
    return m.from == HelmMode::turning && m.to == HelmMode::containing;
  });
  EXPECT_NE(it, r.rec.modes.end());
  // The same cell again, and this time it completes.
  ASSERT_GE(r.rec.started.size(), 2u);
  EXPECT_EQ(r.rec.started[1].task.index, 0u);
  EXPECT_EQ(r.rec.started[1].task.attempts, 1);
  EXPECT_EQ(r.rec.count(TurnStatus::ok), static_cast<int>(plan_turns(r.config).size()));
  EXPECT_EQ(r.runner.cells()[0].aborted, 1);
  EXPECT_EQ(r.runner.turns_given_up(), 0u);
}

// The same start with the foresight on: 10 m of room ahead is less than the 40 m that 30 s at
// 1 m/s and the turn's room need, so the helm turns inward before it sets conditions, and the
// turn never meets the buffer.
TEST(MissionRunner, TooLittleRoomAheadTurnsBackBeforeConditioning) {
  MissionConfig c = turns_config({1.0}, {90}, DirectionPolicy::right, square_region(50, 10));
  ASSERT_DOUBLE_EQ(c.condition_set.run_ahead_s, 30.0);
  Sim r(c, FakeVehicle(30, 0, 90, 1.0));
  r.vehicle.yaw_rate_dps = 5.0;
  ASSERT_TRUE(r.finish());
  EXPECT_EQ(r.runner.state(), MissionState::done);
  const auto* back = r.rec.event(EventKind::turning_back, "turning to");
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(r.rec.event(EventKind::containment, ""), nullptr);
  EXPECT_EQ(r.rec.count(TurnStatus::aborted), 0);
  EXPECT_EQ(r.rec.count(TurnStatus::ok), 1);
  for (const auto& e : r.rec.episodes)
    EXPECT_NE(e.outcome, ConditionSetEpisode::Outcome::interrupted);
  // Conditions were set on the inward course: the turn started heading west-ish (the interior
  // point is the origin, the boat was at x = 30 heading east).
  ASSERT_EQ(r.rec.started.size(), 1u);
  EXPECT_GT(std::abs(k::angle180_deg(r.rec.started[0].turn.start.heading_deg - 90.0)), 90.0);
}

// ---- 5. max_attempts ------------------------------------------------------------------------

TEST(MissionRunner, CellThatAlwaysHitsTheBufferIsGivenUpAndTheMissionFinishes) {
  MissionConfig c = turns_config({1.0}, {90, 180}, DirectionPolicy::right, square_region(100, 10));
  c.turn_array.max_attempts = 2;
  Sim r(c, FakeVehicle(0, 0, 0));
  // Every 180-degree turn is pushed into the buffer behind the vehicle a second after it starts
  // (so that containment heads on inward rather than out of the region).
  const Hook push = [&](double t) {
    const auto& last = r.rec.started;
    if (r.runner.mode() != HelmMode::turning || last.back().task.dheading_deg != 180.0 ||
        t - last.back().turn.start.t_s < 1.0 ||
        r.runner.container().zone({r.vehicle.x(), r.vehicle.y()}) != RegionZone::interior)
      return;
    const double east = std::sin(k::deg_to_rad(r.vehicle.heading()));
    const double north = std::cos(k::deg_to_rad(r.vehicle.heading()));
    if (std::abs(east) >= std::abs(north)) {
      r.vehicle.teleport(east > 0 ? -95.0 : 95.0, r.vehicle.y());
    } else {
      r.vehicle.teleport(r.vehicle.x(), north > 0 ? -95.0 : 95.0);
    }
  };
  ASSERT_TRUE(r.finish(600, push));
  EXPECT_EQ(r.runner.state(), MissionState::done);
  const auto path = r.rec.mode_path();
  EXPECT_EQ(std::vector<HelmMode>(path.end() - 2, path.end()),
            (std::vector<HelmMode>{HelmMode::returning, HelmMode::done}));
  ASSERT_EQ(r.rec.turns.size(), 3u);
  EXPECT_EQ(r.rec.turns[0].status, TurnStatus::ok);
  for (int i : {1, 2}) {
    EXPECT_EQ(r.rec.turns[i].status, TurnStatus::aborted);
    EXPECT_EQ(r.rec.turns[i].task.index, 1u);
    EXPECT_EQ(r.rec.turns[i].task.attempts, i);
  }
  EXPECT_TRUE(r.rec.turns[1].requeued);
  EXPECT_FALSE(r.rec.turns[1].given_up);
  EXPECT_FALSE(r.rec.turns[2].requeued);
  EXPECT_TRUE(r.rec.turns[2].given_up);
  EXPECT_EQ(r.runner.turns_given_up(), 1u);
  EXPECT_EQ(r.runner.cells()[1].given_up, 1);
  EXPECT_EQ(r.runner.cells()[1].aborted, 2);
  EXPECT_TRUE(r.runner.queue().empty());
  EXPECT_NE(r.rec.event(EventKind::turn_aborted, "given up after 2 attempts"), nullptr);
}

// ---- 6. Region exit -------------------------------------------------------------------------

TEST(MissionRunner, LeavingTheRegionHaltsAndAbortsTheTurn) {
  Sim r(turns_config({1.0}, {90}, DirectionPolicy::right, square_region(200, 20)),
        FakeVehicle(0, 0, 0));
  ASSERT_TRUE(r.until_mode(HelmMode::turning));
  r.run_for(1.0);
  r.run_for(0.2, [&](double) { r.vehicle.teleport(250, 0); });
  EXPECT_EQ(r.runner.mode(), HelmMode::halted);
  EXPECT_EQ(r.runner.state(), MissionState::halted);
  EXPECT_TRUE(r.runner.finished());
  EXPECT_EQ(r.vehicle.all_stops, 1);
  EXPECT_NE(r.rec.event(EventKind::halted, "left the operating region"), nullptr);
  ASSERT_EQ(r.rec.turns.size(), 1u);
  EXPECT_EQ(r.rec.turns[0].status, TurnStatus::aborted);
  EXPECT_TRUE(contains(r.rec.turns[0].reason, "left the operating region"));
  EXPECT_FALSE(r.runner.desired_heading_deg().has_value());
  // Halted is final: coming back inside changes nothing, and nothing is commanded.
  const std::size_t commands = r.vehicle.commands.size();
  r.vehicle.teleport(0, 0);
  r.run_for(10);
  EXPECT_EQ(r.runner.mode(), HelmMode::halted);
  EXPECT_EQ(r.vehicle.commands.size(), commands);
  EXPECT_FALSE(r.runner.resume(r.now()));
}

// ---- 7. Operator commands -------------------------------------------------------------------

TEST(MissionRunner, PauseDuringATurnThenResumeCompletesTheMission) {
  Sim r(turns_config({1.0}, {40, 90}, DirectionPolicy::alternate, square_region(200, 20)),
        FakeVehicle(0, 0, 0));
  ASSERT_TRUE(r.until_mode(HelmMode::turning));
  r.run_for(1.0);
  ASSERT_TRUE(r.runner.pause(r.now()));
  EXPECT_FALSE(r.runner.pause(r.now()));
  EXPECT_EQ(r.runner.state(), MissionState::paused);
  EXPECT_EQ(r.runner.mode(), HelmMode::paused);
  EXPECT_EQ(r.vehicle.all_stops, 1);
  ASSERT_EQ(r.rec.turns.size(), 1u);
  EXPECT_EQ(r.rec.turns[0].status, TurnStatus::aborted);
  EXPECT_TRUE(r.rec.turns[0].requeued);
  EXPECT_EQ(r.rec.turns[0].task.attempts, 0);  // an operator's pause is not an attempt
  EXPECT_EQ(r.runner.queue().front().attempts, 0);
  // Paused, it keeps station where it was paused: it coasts on, turns back and settles within
  // the hold radius of that point, still paused.
  const avk::kinematics::Point paused_at{r.vehicle.x(), r.vehicle.y()};
  r.run_for(120);
  EXPECT_EQ(r.runner.mode(), HelmMode::paused);
  EXPECT_EQ(r.runner.state(), MissionState::paused);
  EXPECT_LE(avk::kinematics::distance_m({r.vehicle.x(), r.vehicle.y()}, paused_at),
            avk::mission::kDefaultHoldRadiusM);
  ASSERT_TRUE(r.runner.resume(r.now()));
  EXPECT_FALSE(r.runner.resume(r.now()));
  EXPECT_EQ(r.runner.state(), MissionState::running);
  ASSERT_TRUE(r.finish());
  EXPECT_EQ(r.runner.state(), MissionState::done);
  EXPECT_EQ(r.rec.count(TurnStatus::ok), 2);
  EXPECT_EQ(r.rec.turns[1].task.index, 0u);  // the paused turn again
  EXPECT_EQ(r.runner.cells()[0].aborted, 1);
  EXPECT_EQ(r.runner.cells()[0].ok, 1);
}

// A paused mission in a current: without a hold the vehicle would drift 0.27 m/s x 600 s = 162 m;
// paused, it keeps station within the hold radius's reach of where it was paused.
TEST(MissionRunner, APausedMissionHoldsAgainstTheCurrent) {
  Sim r(turns_config({1.0}, {40, 90}, DirectionPolicy::alternate, square_region(400, 20)),
        FakeVehicle(0, 0, 0));
  ASSERT_TRUE(r.until_mode(HelmMode::conditioning));
  ASSERT_TRUE(r.runner.pause(r.now()));
  const avk::kinematics::Point paused_at{r.vehicle.x(), r.vehicle.y()};
  const auto drift = [&](double) {
    r.vehicle.teleport(r.vehicle.x() + 0.027, r.vehicle.y() - 0.0);
  };
  double worst_m = 0.0;
  for (int i = 0; i < 600; ++i) {
    r.run_for(1.0, drift);
    worst_m =
        std::max(worst_m, avk::kinematics::distance_m({r.vehicle.x(), r.vehicle.y()}, paused_at));
  }
  EXPECT_EQ(r.runner.state(), MissionState::paused);
  EXPECT_LT(worst_m, 10.0);
  ASSERT_TRUE(r.runner.resume(r.now()));
  EXPECT_EQ(r.runner.state(), MissionState::running);
}

TEST(MissionRunner, AbortStopsForGood) {
  Sim r(turns_config({1.0}, {40, 90}, DirectionPolicy::alternate, square_region(200, 20)),
        FakeVehicle(0, 0, 0));
  ASSERT_TRUE(r.until_mode(HelmMode::turning));
  r.run_for(1.0);
  ASSERT_TRUE(r.runner.abort(r.now()));
  EXPECT_EQ(r.runner.state(), MissionState::aborted);
  EXPECT_EQ(r.runner.mode(), HelmMode::halted);
  EXPECT_TRUE(r.runner.finished());
  EXPECT_EQ(r.vehicle.all_stops, 1);
  EXPECT_NE(r.rec.event(EventKind::aborted, "aborted by operator"), nullptr);
  ASSERT_EQ(r.rec.turns.size(), 1u);
  EXPECT_EQ(r.rec.turns[0].status, TurnStatus::aborted);
  EXPECT_FALSE(r.runner.pause(r.now()));
  EXPECT_FALSE(r.runner.resume(r.now()));
  EXPECT_FALSE(r.runner.abort(r.now()));
  const std::size_t commands = r.vehicle.commands.size();
  r.run_for(5);
  EXPECT_EQ(r.vehicle.commands.size(), commands);
  EXPECT_EQ(r.rec.states.back(), MissionState::aborted);
}

// ---- 8. Link loss ---------------------------------------------------------------------------

TEST(MissionRunner, LinkLossDuringATurnStopsAndTheMissionContinuesAfterwards) {
  Sim r(turns_config({1.0}, {40, 90}, DirectionPolicy::alternate, square_region(200, 20)),
        FakeVehicle(0, 0, 0));
  ASSERT_TRUE(r.until_mode(HelmMode::turning));
  r.run_for(1.0);
  r.vehicle.deliver_nav = false;
  const double last_nav_s = r.vehicle.last_nav()->t_s;
  r.run_for(2.6);
  ASSERT_EQ(r.rec.turns.size(), 1u);
  const TurnOutcome& t = r.rec.turns[0];
  EXPECT_EQ(t.status, TurnStatus::aborted);
  EXPECT_TRUE(contains(t.reason, "navigation")) << t.reason;
  EXPECT_EQ(t.task.attempts, 1);
  EXPECT_TRUE(t.requeued);
  EXPECT_EQ(r.vehicle.all_stops, 1);
  EXPECT_EQ(r.runner.mode(), HelmMode::containing);
  const MissionEventRecord* lost = r.rec.event(EventKind::link, "STALE");
  ASSERT_NE(lost, nullptr);
  EXPECT_GE(lost->t_s, last_nav_s + 2.0 - 1e-9);  // stale only after 2 s without navigation
  EXPECT_LE(lost->t_s, last_nav_s + 2.3);
  const std::size_t commands = r.vehicle.commands.size();
  r.run_for(0.4);
  EXPECT_EQ(r.vehicle.commands.size(), commands);  // holding: nothing commanded
  r.vehicle.deliver_nav = true;
  ASSERT_TRUE(r.finish());
  EXPECT_NE(r.rec.event(EventKind::link, "back"), nullptr);
  EXPECT_EQ(r.runner.state(), MissionState::done);
  EXPECT_EQ(r.rec.count(TurnStatus::ok), 2);
}

// ---- 13. ConditionSet timeout ---------------------------------------------------------------

TEST(MissionRunner, ConditionsNeverSetTimeOutAndTheTaskIsGivenUp) {
  MissionConfig c = turns_config({1.0}, {90}, DirectionPolicy::right, square_region(200, 20));
  c.condition_set.timeout_s = 10.0;
  c.turn_array.max_attempts = 2;
  Sim r(c, FakeVehicle(0, 0, 0));
  r.vehicle.speed_cap = 0.5;  // never reaches 1.0 m/s
  ASSERT_TRUE(r.finish());
  EXPECT_EQ(r.runner.state(), MissionState::done);
  EXPECT_TRUE(r.rec.started.empty());
  ASSERT_EQ(r.rec.episodes.size(), 2u);
  for (const auto& e : r.rec.episodes) {
    EXPECT_EQ(e.outcome, ConditionSetEpisode::Outcome::timeout);
    EXPECT_GT(e.end_s - e.start_s, c.condition_set.timeout_s);
    EXPECT_LT(e.end_s - e.start_s, c.condition_set.timeout_s + 0.3);
  }
  EXPECT_NE(r.rec.event(EventKind::condition_set_timeout, "attempt 1"), nullptr);
  EXPECT_NE(r.rec.event(EventKind::condition_set_timeout, "attempt 2"), nullptr);
  EXPECT_NE(r.rec.event(EventKind::turn_given_up), nullptr);
  EXPECT_EQ(r.runner.turns_given_up(), 1u);
  EXPECT_EQ(r.runner.cells()[0].given_up, 1);
  const auto path = r.rec.mode_path();
  EXPECT_EQ(path[path.size() - 2], HelmMode::returning);
}
