// Harvesting turns from a navigation log with guidance: synthetic logs with
// known arcs, each way a step is refused counted under its reason, collected turns skipped.
#include "mission/turn_harvester.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "kinematics/angles.hpp"
#include "support/guided_boat.hpp"

namespace {

using avk::kinematics::TurnSource;
using avk::mission::HarvestResult;
using avk::mission::StepRejection;
using avk::testing::Boat;
using avk::testing::GuidedNav;
using avk::testing::kDt;

struct Log {
  Boat boat{0.0, 1.0};
  std::vector<GuidedNav> rows;
  void run(int n, double desired_deg, double desired_mps = 1.0, double rate_dps = 10.0) {
    for (int i = 0; i < n; ++i)
      rows.push_back(boat.step(desired_deg, desired_mps, rate_dps));
  }
  HarvestResult harvest(std::vector<double> collected = {}) const {
    return avk::mission::harvest_turns(rows, collected, {}, "boat", "7");
  }
};

std::size_t count(const HarvestResult& r, StepRejection why) {
  return r.rejected[static_cast<std::size_t>(why)];
}

TEST(TurnHarvester, AStepFromASteadyCourseIsAHarvestedTurnOnItsKnownArc) {
  Log log;
  log.run(40, 0.0);
  log.run(60, 90.0);
  const HarvestResult r = log.harvest();
  EXPECT_EQ(r.steps, 1u);
  EXPECT_EQ(r.rejected_total(), 0u);
  ASSERT_EQ(r.turns.size(), 1u);
  const auto& t = r.turns[0].turn;
  EXPECT_EQ(t.meta().source, TurnSource::harvested);
  EXPECT_EQ(t.meta().mission_id, "7");
  EXPECT_NEAR(t.meta().goal_dheading_deg, 90.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.meta().start_time_s, log.rows[39].nav.t_s);
  // Dead steady before, and completed within the threshold (5 deg of 90): quality from the
  // completion alone, 1 - 0.5 x miss / 5.
  ASSERT_TRUE(t.meta().quality);
  const double miss = std::abs(t.heading_change_deg() - 90.0);
  EXPECT_NEAR(*t.meta().quality, 1.0 - 0.5 * miss / 5.0, 1e-9);
  EXPECT_GE(*t.meta().quality, 0.5);
  // Constant 10 deg/s at 1 m/s: an arc of radius 5.73 m from the start, heading east at its end.
  const double radius_m = 1.0 / avk::kinematics::deg_to_rad(10.0);
  const auto& end = t.samples().back();
  const auto& start = t.samples().front();
  const double turned = avk::kinematics::deg_to_rad(t.heading_change_deg());
  EXPECT_NEAR(end.x_m - start.x_m, radius_m * (1.0 - std::cos(turned)), 0.3);
  EXPECT_NEAR(end.y_m - start.y_m, radius_m * std::sin(turned), 0.3);
}

TEST(TurnHarvester, AStepBeforeTheCourseSettledIsNotSteadyBefore) {
  // 60 deg at 10 deg/s completes within 5 deg after 5.5 s: a step at 6 s comes before the
  // ConditionSet window (5 differences) has filled again; one at 10 s comes from a steady course.
  for (const auto& [rows, harvested] : {std::pair{24, 1u}, std::pair{40, 2u}}) {
    Log log;
    log.run(40, 0.0);
    log.run(rows, 60.0);
    log.run(40, 120.0);
    const HarvestResult r = log.harvest();
    EXPECT_EQ(r.steps, 2u);
    EXPECT_EQ(r.turns.size(), harvested);
    EXPECT_EQ(count(r, StepRejection::not_steady_before), 2u - harvested);
  }
}

TEST(TurnHarvester, EachRefusedStepIsCountedUnderItsReason) {
  Log log;
  log.run(40, 0.0);
  log.run(40, 3.0);  // too small
  log.run(40, 3.0, 1.0, 10.0);
  // Speed: the boat at 1 m/s told 1.5 m/s, then a step.
  log.run(40, 3.0, 1.5);
  log.run(40, 90.0, 1.5);  // speed_not_steady; the boat turns anyway
  log.run(40, 90.0);
  log.run(12, 180.0);  // a turn interrupted by another step 3 s in
  log.run(60, 270.0);  // goal_changed_during_turn, then this step is mid-swing
  log.run(40, 270.0);
  log.run(20, 0.0);  // the log ends during the turn
  const HarvestResult r = log.harvest();
  EXPECT_EQ(count(r, StepRejection::too_small), 1u);
  EXPECT_EQ(count(r, StepRejection::speed_not_steady), 1u);
  EXPECT_EQ(count(r, StepRejection::goal_changed_during_turn), 1u);
  EXPECT_EQ(count(r, StepRejection::not_steady_before), 1u);
  EXPECT_EQ(count(r, StepRejection::never_completed), 1u);
  EXPECT_EQ(r.turns.size(), 0u);
  EXPECT_EQ(r.steps, r.rejected_total());
}

TEST(TurnHarvester, GapsSpeedCommandsAndBearingsAreRefused) {
  Log log;
  log.run(40, 0.0);
  log.rows.push_back(log.boat.step(0.0, 1.0, 10.0, 5.0));  // 5 s without navigation
  log.run(1, 90.0);                                        // a step right after the gap
  log.run(60, 90.0);
  log.run(40, 180.0, 1.2);  // a new speed with the step
  log.run(40, 180.0);
  for (int i = 0; i < 20; ++i)  // a bearing, recomputed every tick
    log.run(1, 180.0 + 0.5 * i);
  log.run(2, 189.5);  // held for two samples: less than the window
  log.run(40, 270.0);
  const HarvestResult r = log.harvest();
  EXPECT_EQ(count(r, StepRejection::log_gap), 1u);
  EXPECT_EQ(count(r, StepRejection::speed_command_changed), 1u);
  EXPECT_EQ(count(r, StepRejection::course_not_held), 1u);
  // The bearing is one step (its first change), not one per tick.
  EXPECT_EQ(count(r, StepRejection::too_small), 1u);
  EXPECT_TRUE(r.turns.empty());
}

TEST(TurnHarvester, StepsACollectionTurnAlreadyHoldsAreSkipped) {
  Log log;
  log.run(40, 0.0);
  log.run(60, 90.0);
  log.run(60, 180.0);
  const std::vector<double> collected = {log.rows[39].nav.t_s};
  const HarvestResult r = log.harvest(collected);
  EXPECT_EQ(r.steps, 2u);
  EXPECT_EQ(r.already_recorded, 1u);
  ASSERT_EQ(r.turns.size(), 1u);
  EXPECT_DOUBLE_EQ(r.turns[0].turn.meta().start_time_s, log.rows[99].nav.t_s);
}

TEST(TurnHarvester, QualityFallsWithTheYawRateAndSpeedErrorAtTheStep) {
  avk::mission::ConditionSetConfig cs;
  avk::mission::CompletionRule done;
  Log log;
  log.run(40, 0.0);
  log.run(60, 90.0);
  const auto turn = log.harvest().turns.at(0).turn;
  const double clean = avk::mission::turn_quality({0.0, 0.0}, turn, cs, done);
  EXPECT_NEAR(avk::mission::turn_quality({0.5, 0.0}, turn, cs, done), 0.75 * clean, 1e-12);
  EXPECT_NEAR(avk::mission::turn_quality({-1.0, 0.1}, turn, cs, done), 0.0, 1e-12);
  EXPECT_NEAR(avk::mission::turn_quality({0.0, -0.05}, turn, cs, done), 0.75 * clean, 1e-12);
}

}  // namespace
