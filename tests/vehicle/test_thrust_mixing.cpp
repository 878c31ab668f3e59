#include <gtest/gtest.h>

#include "vehicle/thrust_mixing.hpp"

using namespace avk::vehicle;

namespace {

void expect_mix(double rudder, double thrust, const MixConfig& c, double left, double right) {
  const DifferentialThrust m = mix_differential(rudder, thrust, c);
  EXPECT_DOUBLE_EQ(m.left_pct, left) << "rudder " << rudder << " thrust " << thrust;
  EXPECT_DOUBLE_EQ(m.right_pct, right) << "rudder " << rudder << " thrust " << thrust;
}

}  // namespace

TEST(ThrustMixing, StraightAndTurning) {
  expect_mix(0.0, 60.0, {}, 60.0, 60.0);
  expect_mix(20.0, 50.0, {}, 70.0, 30.0);   // starboard: left pushes harder
  expect_mix(-20.0, 50.0, {}, 30.0, 70.0);  // port
}

TEST(ThrustMixing, RudderAndThrustClamped) {
  expect_mix(80.0, 0.0, {}, 50.0, -50.0);  // rudder limited to the 50 % mix
  expect_mix(0.0, 150.0, {}, 100.0, 100.0);
  MixConfig narrow;
  narrow.max_rudder_mix_pct = 10.0;
  expect_mix(40.0, 50.0, narrow, 60.0, 40.0);
}

TEST(ThrustMixing, OverflowSpillsToTheOtherSide) {
  // L = 130, R = 50: the 30 over the top comes off the right side.
  expect_mix(40.0, 90.0, {}, 100.0, 20.0);
  // Mirror: R = 130 -> left loses 30.
  expect_mix(-40.0, 90.0, {}, 20.0, 100.0);
  // Full thrust, full mix: L = 150 -> R = 50 - 50.
  expect_mix(50.0, 100.0, {}, 100.0, 0.0);
}

TEST(ThrustMixing, NegativeOverflowSpillsToo) {
  // L = -60, R = -120: R is 20 below -100, so L -= -20 -> L = -40.
  expect_mix(30.0, -90.0, {}, -40.0, -100.0);
  // L = -120, R = -60: R -= -20 -> -40.
  expect_mix(-30.0, -90.0, {}, -100.0, -40.0);
}

TEST(ThrustMixing, MaxThrustScales) {
  MixConfig half;
  half.max_thrust_pct = 50.0;
  expect_mix(20.0, 50.0, half, 35.0, 15.0);  // (70, 30) · 0.5
  // (130, 50) · 0.5 = (65, 25); 15 over 50 comes off the right.
  expect_mix(40.0, 90.0, half, 50.0, 10.0);
  expect_mix(0.0, 100.0, half, 50.0, 50.0);
}
