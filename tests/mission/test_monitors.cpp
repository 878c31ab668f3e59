#include <gtest/gtest.h>

#include "mission/condition_set.hpp"
#include "mission/turn_monitor.hpp"

using namespace avk::mission;
using avk::vehicle::NavSample;

namespace {
NavSample nav(double t, double heading, double speed = 1.0, double x = 0, double y = 0) {
  NavSample n;
  n.t_s = t;
  n.heading_deg = heading;
  n.speed_mps = speed;
  n.x_m = x;
  n.y_m = y;
  return n;
}
}  // namespace

TEST(ConditionSet, NeedsAFullWindowOfSteadyHeadingAtSpeed) {
  ConditionSetMonitor m({0.1, 1.0, 5, 60}, 1.0);
  // Six samples give five yaw rates; only then can conditions be set.
  for (int k = 0; k < 5; ++k)
    EXPECT_FALSE(m.update(nav(k * 0.25, 10.0)));
  EXPECT_TRUE(m.update(nav(1.25, 10.0)));
  EXPECT_FALSE(m.update(nav(1.5, 10.0, 1.2)));  // speed off by 0.2
}

TEST(ConditionSet, YawRateIsWrapAwareMovingAverage) {
  ConditionSetMonitor m({0.1, 1.0, 4, 60}, 1.0);
  // 358, 359, 0, 1, 2 degrees one second apart: +1 deg/s, not -359.
  for (int k = 0; k < 5; ++k)
    m.update(nav(k, 358.0 + k >= 360.0 ? k - 2.0 : 358.0 + k));
  ASSERT_TRUE(m.yaw_rate_dps().has_value());
  EXPECT_DOUBLE_EQ(*m.yaw_rate_dps(), 1.0);
  EXPECT_TRUE(m.conditions_set());  // 1 deg/s is within the limit
  m.update(nav(5, 5.0));            // +3 deg/s enters the window: mean (1+1+1+3)/4
  EXPECT_DOUBLE_EQ(*m.yaw_rate_dps(), 1.5);
  EXPECT_FALSE(m.conditions_set());
}

TEST(TurnMonitor, CompletesWithinTheThreshold) {
  TurnMonitor t(nav(0, 350), 1.0, 60.0, 5.0);  // goal 50 across north
  EXPECT_DOUBLE_EQ(t.goal_heading_deg(), 50.0);
  EXPECT_EQ(t.update(nav(1, 10)), Completion::none);
  EXPECT_EQ(t.update(nav(2, 30)), Completion::none);
  EXPECT_EQ(t.update(nav(3, 46)), Completion::within_threshold);
  const auto turn = t.build("v", "m");
  EXPECT_EQ(turn.samples().size(), 4u);
  EXPECT_DOUBLE_EQ(turn.meta().observed_dheading_deg, 56.0);
}

TEST(TurnMonitor, CompletesWhenTheHeadingPassesTheGoalBetweenSamples) {
  TurnMonitor t(nav(0, 0), 1.0, 90.0, 2.0);
  EXPECT_EQ(t.update(nav(1, 60)), Completion::none);
  EXPECT_EQ(t.update(nav(2, 85)), Completion::none);
  EXPECT_EQ(t.update(nav(3, 97)), Completion::passed_goal);  // never within 2 deg
  EXPECT_EQ(t.update(nav(4, 91)), Completion::passed_goal);  // stays complete, records no more
  EXPECT_EQ(t.sample_count(), 4u);
}

TEST(TurnMonitor, LeftTurnsCompleteToo) {
  TurnMonitor t(nav(0, 20), 1.0, -100.0, 3.0);  // goal 280
  EXPECT_EQ(t.update(nav(1, 340)), Completion::none);
  EXPECT_EQ(t.update(nav(2, 300)), Completion::none);
  EXPECT_EQ(t.update(nav(3, 275)), Completion::passed_goal);
  TurnMonitor u(nav(0, 20), 1.0, -100.0, 3.0);
  EXPECT_EQ(u.update(nav(1, 282)), Completion::within_threshold);
}
