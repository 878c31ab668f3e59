// Turn extraction from a navigation log with guidance: synthetic runs (steady course, a step in
// the desired heading, an arc) and the ways a turn is refused, aborted or rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "kinematics/angles.hpp"
#include "mission/turn_extractor.hpp"
#include "support/guided_boat.hpp"

namespace {

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using avk::mission::TurnExtractor;
using avk::vehicle::GuidedNav;

using avk::testing::Boat;
using avk::testing::kDt;

struct Collected {
  std::vector<TurnSequence> turns;
  void take(std::optional<TurnSequence> t) {
    if (t) turns.push_back(std::move(*t));
  }
};

TurnExtractor extractor() {
  return TurnExtractor({}, "boat", "imported-1");
}

TEST(TurnExtractor, SteadyRunThenAStepGivesOneOkTurnWhoseGoalIsTheStep) {
  TurnExtractor x = extractor();
  Boat boat(30.0, 1.0);
  Collected run;
  for (int i = 0; i < 40; ++i)
    run.take(x.feed(boat.step(30.0, 1.0, 10.0)));
  const double start_t = 100.0 + 39 * kDt;  // the last sample before the step
  for (int i = 0; i < 80; ++i)
    run.take(x.feed(boat.step(120.0, 1.0, 10.0)));
  run.take(x.finish());
  ASSERT_EQ(run.turns.size(), 1u);
  const TurnSequence& t = run.turns[0];
  EXPECT_EQ(t.meta().status, TurnStatus::ok) << t.meta().status_reason;
  EXPECT_TRUE(t.meta().status_reason.empty());
  EXPECT_NEAR(t.meta().goal_dheading_deg, 90.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.meta().commanded_speed_mps, 1.0);
  EXPECT_DOUBLE_EQ(t.meta().start_time_s, start_t);
  EXPECT_DOUBLE_EQ(t.samples().front().heading_deg, 30.0);
  EXPECT_LE(std::abs(t.meta().observed_dheading_deg - 90.0), 5.0);
  EXPECT_GE(t.meta().observed_dheading_deg, 85.0);
  EXPECT_EQ(t.meta().vehicle_id, "boat");
  EXPECT_EQ(t.meta().mission_id, "imported-1");
  // At 10 deg/s a 90-degree turn takes 9 s, completed within 5 deg of the goal: ~8.5 s.
  EXPECT_NEAR(t.meta().end_time_s - t.meta().start_time_s, 8.5, 0.5);
  EXPECT_FALSE(x.turning());
}

TEST(TurnExtractor, LeftTurnsAcrossNorthHaveANegativeGoal) {
  TurnExtractor x = extractor();
  Boat boat(20.0, 1.5);
  Collected run;
  for (int i = 0; i < 20; ++i)
    run.take(x.feed(boat.step(20.0, 1.5, 8.0)));
  for (int i = 0; i < 80; ++i)
    run.take(x.feed(boat.step(300.0, 1.5, 8.0)));
  ASSERT_EQ(run.turns.size(), 1u);
  EXPECT_EQ(run.turns[0].meta().status, TurnStatus::ok) << run.turns[0].meta().status_reason;
  EXPECT_NEAR(run.turns[0].meta().goal_dheading_deg, -80.0, 1e-9);
  EXPECT_NEAR(run.turns[0].meta().observed_dheading_deg, -80.0, 5.0);
}

TEST(TurnExtractor, TurnsFollowOneAnotherOnceTheCourseIsSteadyAgain) {
  TurnExtractor x = extractor();
  Boat boat(0.0, 1.0);
  Collected run;
  double desired = 0.0;
  for (int turn = 0; turn < 3; ++turn) {
    for (int i = 0; i < 40; ++i)
      run.take(x.feed(boat.step(desired, 1.0, 10.0)));
    desired = avk::kinematics::wrap360_deg(desired + 60.0);
  }
  run.take(x.finish());
  ASSERT_EQ(run.turns.size(), 2u);  // the third step is never fed
  for (const auto& t : run.turns) {
    EXPECT_EQ(t.meta().status, TurnStatus::ok);
    EXPECT_NEAR(t.meta().goal_dheading_deg, 60.0, 1e-9);
  }
}

TEST(TurnExtractor, AStepInterruptedByAnotherStepIsAborted) {
  TurnExtractor x = extractor();
  Boat boat(0.0, 1.0);
  Collected run;
  for (int i = 0; i < 20; ++i)
    run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
  for (int i = 0; i < 12; ++i)  // 3 s of a 9 s turn
    run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
  for (int i = 0; i < 60; ++i)
    run.take(x.feed(boat.step(200.0, 1.0, 10.0)));
  run.take(x.finish());
  ASSERT_EQ(run.turns.size(), 1u);  // the second step is not from a steady course
  EXPECT_EQ(run.turns[0].meta().status, TurnStatus::aborted);
  EXPECT_EQ(run.turns[0].meta().status_reason, "the desired heading changed before completion");
  EXPECT_NEAR(run.turns[0].meta().goal_dheading_deg, 90.0, 1e-9);
  EXPECT_EQ(run.turns[0].samples().size(), 13u);  // start + the 12 samples of the first step
}

TEST(TurnExtractor, ASpeedChangeAGapOrTheEndOfTheLogAbortsTheTurn) {
  {
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 20; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 4; ++i)
      run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    run.take(x.feed(boat.step(90.0, 1.5, 10.0)));
    ASSERT_EQ(run.turns.size(), 1u);
    EXPECT_EQ(run.turns[0].meta().status, TurnStatus::aborted);
    EXPECT_EQ(run.turns[0].meta().status_reason, "the desired speed changed before completion");
  }
  {
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 20; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 4; ++i)
      run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    boat.step(90.0, 1.0, 10.0, 2.5);  // logged nothing for 2.5 s
    run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    ASSERT_EQ(run.turns.size(), 1u);
    EXPECT_EQ(run.turns[0].meta().status, TurnStatus::aborted);
    EXPECT_EQ(run.turns[0].meta().status_reason, "navigation gap of 2.75 s");
  }
  {
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 20; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 4; ++i)
      run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    EXPECT_TRUE(x.turning());
    run.take(x.finish());
    ASSERT_EQ(run.turns.size(), 1u);
    EXPECT_EQ(run.turns[0].meta().status, TurnStatus::aborted);
    EXPECT_EQ(run.turns[0].meta().status_reason, "the log ended during the turn");
  }
}

TEST(TurnExtractor, NoStepNoTurn) {
  TurnExtractor x = extractor();
  Boat boat(45.0, 1.0);
  Collected run;
  for (int i = 0; i < 400; ++i)
    run.take(x.feed(boat.step(45.0, 1.0, 10.0)));
  run.take(x.finish());
  EXPECT_TRUE(run.turns.empty());
}

TEST(TurnExtractor, ADesiredHeadingThatIsNeverHeldGivesNoTurn) {
  // A bearing to a point recomputed every tick from noisy positions: it jumps by up to 8 deg
  // while the boat holds its course, but it is never held, so none of its jumps is a command.
  TurnExtractor x = extractor();
  Boat boat(45.0, 1.0);
  Collected run;
  for (int i = 0; i < 400; ++i)
    run.take(x.feed(boat.step(45.0 + 8.0 * std::sin(i * 0.7), 1.0, 0.0)));
  run.take(x.finish());
  EXPECT_TRUE(run.turns.empty());
}

TEST(TurnExtractor, TheStepIsMeasuredFromTheCourseTheVehicleHolds) {
  // In a cross wind the boat holds a steady course 9 deg off its desired heading; a change of
  // the desired heading by 1 deg then commands a 10-deg turn (as the mission does: its goal is
  // start heading + the cell's heading change).
  TurnExtractor x = extractor();
  Boat boat(0.0, 1.0);
  Collected run;
  for (int i = 0; i < 30; ++i)
    run.take(x.feed(boat.step(9.0, 1.0, 0.0)));
  for (int i = 0; i < 30; ++i)
    run.take(x.feed(boat.step(10.0, 1.0, 10.0)));
  ASSERT_EQ(run.turns.size(), 1u);
  EXPECT_EQ(run.turns[0].meta().status, TurnStatus::ok) << run.turns[0].meta().status_reason;
  EXPECT_NEAR(run.turns[0].meta().goal_dheading_deg, 10.0, 1e-9);
}

TEST(TurnExtractor, AStepWhileNotSteadyIsNotATurn) {
  {
    // Yawing at 3 deg/s, above the 1 deg/s limit, when the step comes.
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 40; ++i) {
      boat.drift(3.0);
      boat.apply_drift();
      run.take(x.feed(boat.step(0.0, 1.0, 0.0)));
    }
    for (int i = 0; i < 60; ++i)
      run.take(x.feed(boat.step(120.0, 1.0, 10.0)));
    run.take(x.finish());
    EXPECT_TRUE(run.turns.empty());
  }
  {
    // On course but 0.3 m/s slower than desired.
    TurnExtractor x = extractor();
    Boat boat(0.0, 0.7);
    Collected run;
    for (int i = 0; i < 40; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 60; ++i)
      run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    EXPECT_TRUE(run.turns.empty());
  }
  {
    // Steady, but the desired speed changed with the step: a new speed is not a turn of a cell.
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 40; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 60; ++i)
      run.take(x.feed(boat.step(90.0, 1.2, 10.0)));
    EXPECT_TRUE(run.turns.empty());
  }
  {
    // Too few samples since the guidance began to fill the yaw-rate window (5 differences).
    TurnExtractor x = extractor();
    Boat boat(0.0, 1.0);
    Collected run;
    for (int i = 0; i < 10; ++i)
      run.take(x.feed(boat.step(std::nullopt, std::nullopt, 0.0)));
    for (int i = 0; i < 5; ++i)
      run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
    for (int i = 0; i < 60; ++i)
      run.take(x.feed(boat.step(90.0, 1.0, 10.0)));
    EXPECT_TRUE(run.turns.empty());
  }
}

TEST(TurnExtractor, ATurnTheChecksRefuseIsRejectedWithTheirReason) {
  // A 6-degree step completed (within its 1-degree threshold, 10 % of the step) by the first
  // sample after it: two samples are too few for a turn.
  TurnExtractor x = extractor();
  Boat boat(0.0, 1.0);
  Collected run;
  for (int i = 0; i < 20; ++i)
    run.take(x.feed(boat.step(0.0, 1.0, 10.0)));
  boat.set_heading(5.5);
  for (int i = 0; i < 10; ++i)
    run.take(x.feed(boat.step(6.0, 1.0, 10.0)));
  ASSERT_EQ(run.turns.size(), 1u);
  EXPECT_EQ(run.turns[0].meta().status, TurnStatus::rejected);
  EXPECT_NE(run.turns[0].meta().status_reason.find("too_few_samples"), std::string::npos)
      << run.turns[0].meta().status_reason;
}

}  // namespace
