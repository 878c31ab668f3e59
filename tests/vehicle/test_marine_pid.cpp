#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "vehicle/marine_pid.hpp"

using namespace avk::vehicle;

// ---- ScalarPid -------------------------------------------------------------------------------

TEST(ScalarPid, FirstCallHasNoDerivative) {
  ScalarPid pid(PidGains{0.0, 1.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(pid.run(5.0, 10.0), 0.0);
}

TEST(ScalarPid, DerivativeIsMeanOfLastNineSlopes) {
  // e = k² at t = k/2: the slope between calls k-1 and k is (2k-1)/0.5 = 4k-2.
  ScalarPid pid(PidGains{0.0, 1.0, 0.0, 0.0});
  pid.run(0.0, 0.0);
  double out = 0.0;
  for (int k = 1; k <= 3; ++k)
    out = pid.run(k * k, k * 0.5);
  EXPECT_DOUBLE_EQ(out, (2.0 + 6.0 + 10.0) / 3.0);  // fewer than nine: mean of all
  for (int k = 4; k <= 9; ++k)
    out = pid.run(k * k, k * 0.5);
  EXPECT_DOUBLE_EQ(out, 18.0);  // slopes 2, 6, ..., 34: exactly nine, mean 18
  out = pid.run(100.0, 5.0);
  // Ten slopes so far; the window drops the first (2): 6, 10, ..., 38 -> mean 22 (all ten: 20).
  EXPECT_DOUBLE_EQ(out, 22.0);
  EXPECT_DOUBLE_EQ(pid.derivative(), 22.0);
}

TEST(ScalarPid, ZeroDtReturnsPreviousOutput) {
  ScalarPid pid(PidGains{2.0, 1.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(pid.run(1.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(pid.run(7.0, 0.0), 2.0);  // not 14: same instant, nothing new
  // The ignored error must not become the previous error: slope (3 - 1)/1, not (3 - 7)/1.
  EXPECT_DOUBLE_EQ(pid.run(3.0, 1.0), 2.0 * 3.0 + 2.0);
}

TEST(ScalarPid, NegativeDtThrows) {
  ScalarPid pid;
  pid.run(1.0, 5.0);
  EXPECT_THROW(pid.run(1.0, 4.9), std::invalid_argument);
  // After a reset the next call is a first call: any time is fine.
  pid.reset();
  EXPECT_DOUBLE_EQ(pid.run(1.0, 1.0), 1.0);
}

TEST(ScalarPid, IntegralAccumulatesAndIsClamped) {
  ScalarPid pid(PidGains{0.0, 0.0, 0.5, 2.0});
  EXPECT_DOUBLE_EQ(pid.run(2.0, 0.0), 0.0);  // first call: dt = 0, nothing integrated
  EXPECT_DOUBLE_EQ(pid.run(2.0, 1.0), 1.0);  // 0.5 * 2 * 1
  EXPECT_DOUBLE_EQ(pid.run(2.0, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(pid.run(2.0, 3.0), 2.0);     // 3 clamped to the limit 2
  EXPECT_DOUBLE_EQ(pid.run(-2.0, 4.0), 1.0);    // unwinds from the clamp, not from 3
  EXPECT_DOUBLE_EQ(pid.run(-10.0, 5.0), -2.0);  // 1 - 5 clamped to -2
  EXPECT_DOUBLE_EQ(pid.integral(), -2.0);
}

TEST(ScalarPid, ZeroKiKeepsIntegralZero) {
  ScalarPid pid(PidGains{1.0, 0.0, 0.0, 5.0});
  pid.run(3.0, 0.0);
  EXPECT_DOUBLE_EQ(pid.run(3.0, 1.0), 3.0);
  EXPECT_DOUBLE_EQ(pid.integral(), 0.0);
  ScalarPid negative(PidGains{1.0, 0.0, -0.5, 5.0});  // Ki < 0 is "off" too
  negative.run(3.0, 0.0);
  EXPECT_DOUBLE_EQ(negative.run(3.0, 1.0), 3.0);
  EXPECT_DOUBLE_EQ(negative.integral(), 0.0);
}

TEST(ScalarPid, OutputClampedToHundred) {
  ScalarPid pid(PidGains{10.0, 0.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(pid.run(50.0, 0.0), 100.0);
  EXPECT_DOUBLE_EQ(pid.run(-50.0, 1.0), -100.0);
  EXPECT_DOUBLE_EQ(pid.run(5.0, 2.0), 50.0);
}

TEST(ScalarPid, NonFiniteGainsThrow) {
  EXPECT_THROW(ScalarPid(PidGains{std::numeric_limits<double>::quiet_NaN(), 0, 0, 0}),
               std::invalid_argument);
}

// ---- MarinePid -------------------------------------------------------------------------------

namespace {

NavSample nav_at(double t, double heading_deg, double speed_mps) {
  NavSample n;
  n.t_s = t;
  n.heading_deg = heading_deg;
  n.speed_mps = speed_mps;
  return n;
}

}  // namespace

TEST(MarinePid, PresetsMatchTheThesisTables) {
  const MarinePidConfig sim = MarinePidConfig::thesis_sim();
  EXPECT_DOUBLE_EQ(sim.yaw.kp, 1.0);
  EXPECT_DOUBLE_EQ(sim.yaw.ki, 0.0);
  EXPECT_DOUBLE_EQ(sim.speed.kp, 1.0);
  EXPECT_DOUBLE_EQ(sim.max_rudder_pct, 40.0);
  EXPECT_DOUBLE_EQ(sim.max_thrust_pct, 100.0);
  EXPECT_DOUBLE_EQ(sim.speed_factor, 0.0);
  EXPECT_DOUBLE_EQ(sim.tardy_s, 2.0);
  const MarinePidConfig m200 = MarinePidConfig::m200_in_water();
  EXPECT_DOUBLE_EQ(m200.yaw.kp, 0.5);
  EXPECT_DOUBLE_EQ(m200.yaw.ki, 0.0);  // the lower end of 0-0.05: docs/sim-config.md
  EXPECT_DOUBLE_EQ(m200.yaw.integral_limit, 20.0);
  EXPECT_DOUBLE_EQ(m200.speed.kp, 1.0);
}

TEST(MarinePid, StarboardDesiredGivesPositiveRudder) {
  MarinePid pid;
  // Moving from rest, so the incremental speed controller gives thrust 1 and the rudder survives.
  const ActuatorCommand a = pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 30.0, 1.0});
  EXPECT_DOUBLE_EQ(a.thrust_pct, 1.0);
  EXPECT_DOUBLE_EQ(a.rudder_pct, 30.0);  // error 0 - 30 = -30, rudder = -Kp·e
  EXPECT_FALSE(a.left_pct.has_value());
}

TEST(MarinePid, PortDesiredGivesNegativeRudder) {
  MarinePid pid;
  const ActuatorCommand a = pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 330.0, 1.0});
  EXPECT_DOUBLE_EQ(a.rudder_pct, -30.0);
}

TEST(MarinePid, RudderClampedToMaxRudder) {
  MarinePid pid;
  EXPECT_DOUBLE_EQ(pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 90.0, 1.0}).rudder_pct,
                   40.0);
  EXPECT_DOUBLE_EQ(
      pid.step(0.25, nav_at(0.25, 0.0, 0.0), DesiredCommand{0.25, 270.0, 1.0}).rudder_pct, -40.0);
}

TEST(MarinePid, HeadingErrorWrapsTheShortWay) {
  MarinePid pid;
  // 350 -> 10 is 20 degrees to starboard, not 340 to port.
  const ActuatorCommand a = pid.step(0.0, nav_at(0.0, 350.0, 0.0), DesiredCommand{0.0, 10.0, 1.0});
  EXPECT_DOUBLE_EQ(a.rudder_pct, 20.0);
  MarinePid back;
  const ActuatorCommand b = back.step(0.0, nav_at(0.0, 10.0, 0.0), DesiredCommand{0.0, 350.0, 1.0});
  EXPECT_DOUBLE_EQ(b.rudder_pct, -20.0);
}

TEST(MarinePid, SpeedFactorIsOpenLoop) {
  MarinePidConfig c;
  c.speed_factor = 25.0;
  MarinePid pid(c);
  // Measured speed does not matter.
  EXPECT_DOUBLE_EQ(pid.step(0.0, nav_at(0.0, 0.0, 3.0), DesiredCommand{0.0, 0.0, 1.2}).thrust_pct,
                   30.0);
  EXPECT_DOUBLE_EQ(
      pid.step(0.25, nav_at(0.25, 0.0, 0.0), DesiredCommand{0.25, 0.0, 1.2}).thrust_pct, 30.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 30.0);
  EXPECT_DOUBLE_EQ(pid.step(0.5, nav_at(0.5, 0.0, 0.0), DesiredCommand{0.5, 0.0, 5.0}).thrust_pct,
                   100.0);  // 125 clamped to max thrust
}

TEST(MarinePid, IncrementalThrustBuildsOnMemory) {
  MarinePid pid;
  auto thrust = [&](double t, double speed) {
    return pid.step(t, nav_at(t, 0.0, speed), DesiredCommand{t, 0.0, 2.0}).thrust_pct;
  };
  EXPECT_DOUBLE_EQ(thrust(0.0, 0.0), 2.0);   // 0 + (2 - 0)
  EXPECT_DOUBLE_EQ(thrust(0.25, 0.5), 3.5);  // 2 + (2 - 0.5)
  EXPECT_DOUBLE_EQ(thrust(0.5, 4.0), 1.5);   // 3.5 + (2 - 4)
  EXPECT_DOUBLE_EQ(thrust(0.75, 6.0), 0.0);  // 1.5 - 4 < 0: no reverse
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 0.0);
  EXPECT_DOUBLE_EQ(thrust(1.0, 1.0), 1.0);  // starts again from 0, not from -2.5
}

TEST(MarinePid, IncrementalThrustClampedToMaxThrust) {
  MarinePidConfig c;
  c.max_thrust_pct = 5.0;
  MarinePid pid(c);
  EXPECT_DOUBLE_EQ(pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 0.0, 10.0}).thrust_pct,
                   5.0);
  EXPECT_DOUBLE_EQ(
      pid.step(0.25, nav_at(0.25, 0.0, 0.0), DesiredCommand{0.25, 0.0, 10.0}).thrust_pct, 5.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 5.0);  // memory holds the clamped value, not 15
}

TEST(MarinePid, TinyDesiredSpeedStopsThrustAndRudder) {
  MarinePidConfig c;
  c.speed_factor = 1000.0;  // 0.0005 m/s would otherwise give 0.5 % thrust
  MarinePid pid(c);
  const ActuatorCommand a = pid.step(0.0, nav_at(0.0, 0.0, 1.0), DesiredCommand{0.0, 90.0, 0.0005});
  EXPECT_DOUBLE_EQ(a.thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(a.rudder_pct, 0.0);
  MarinePid incremental;
  const ActuatorCommand b =
      incremental.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 90.0, 0.001});
  EXPECT_DOUBLE_EQ(b.thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(b.rudder_pct, 0.0);
  EXPECT_DOUBLE_EQ(incremental.thrust_memory_pct(), 0.0);
  // Just above the dead band the controller acts.
  MarinePid above;
  EXPECT_GT(above.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 90.0, 0.002}).rudder_pct,
            0.0);
}

TEST(MarinePid, ZeroThrustZeroesRudder) {
  MarinePid pid;
  // At the desired speed with no thrust memory the increment is 0: no thrust, so no rudder.
  const ActuatorCommand a = pid.step(0.0, nav_at(0.0, 0.0, 1.0), DesiredCommand{0.0, 90.0, 1.0});
  EXPECT_DOUBLE_EQ(a.thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(a.rudder_pct, 0.0);
}

TEST(MarinePid, TardyNavigationStopsAndResetsMemory) {
  MarinePid pid;
  const DesiredCommand want{0.0, 45.0, 1.0};
  pid.step(0.0, nav_at(0.0, 0.0, 0.0), want);
  EXPECT_DOUBLE_EQ(pid.step(1.0, nav_at(1.0, 0.0, 0.0), DesiredCommand{1.0, 45.0, 1.0}).thrust_pct,
                   2.0);
  // Navigation exactly tardy_s old is still fine...
  EXPECT_DOUBLE_EQ(pid.step(3.0, nav_at(1.0, 0.0, 0.0), DesiredCommand{3.0, 45.0, 1.0}).thrust_pct,
                   3.0);
  // ...a moment later it is not.
  const ActuatorCommand a = pid.step(3.01, nav_at(1.0, 0.0, 0.0), DesiredCommand{3.01, 45.0, 1.0});
  EXPECT_DOUBLE_EQ(a.thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(a.rudder_pct, 0.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 0.0);
  EXPECT_TRUE(pid.paused());
  // Fresh navigation: the incremental controller starts from 0 again.
  EXPECT_DOUBLE_EQ(
      pid.step(3.25, nav_at(3.25, 0.0, 0.0), DesiredCommand{3.25, 45.0, 1.0}).thrust_pct, 1.0);
  EXPECT_FALSE(pid.paused());
  // No navigation at all is tardy too.
  EXPECT_DOUBLE_EQ(pid.step(3.5, std::nullopt, DesiredCommand{3.5, 45.0, 1.0}).thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 0.0);
}

TEST(MarinePid, TardyDesiredStopsAndResetsMemory) {
  MarinePid pid;
  pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 1.0);
  const ActuatorCommand a = pid.step(2.5, nav_at(2.5, 0.0, 0.0), DesiredCommand{0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(a.thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 0.0);
  pid.step(2.75, nav_at(2.75, 0.0, 0.0), DesiredCommand{2.75, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 1.0);
  EXPECT_DOUBLE_EQ(pid.step(3.0, nav_at(3.0, 0.0, 0.0), std::nullopt).thrust_pct, 0.0);
  EXPECT_DOUBLE_EQ(pid.thrust_memory_pct(), 0.0);
}

TEST(MarinePid, TardyResetsThePids) {
  // With an integral term, a reset is visible: after the pause the integral starts from zero.
  MarinePidConfig c;
  c.yaw = PidGains{0.0, 0.0, 1.0, 50.0};
  MarinePid pid(c);
  pid.step(0.0, nav_at(0.0, 0.0, 0.0), DesiredCommand{0.0, 10.0, 1.0});
  // I = 1 * (-10) * 1 = -10 -> rudder +10
  EXPECT_DOUBLE_EQ(pid.step(1.0, nav_at(1.0, 0.0, 0.0), DesiredCommand{1.0, 10.0, 1.0}).rudder_pct,
                   10.0);
  pid.step(5.0, std::nullopt, std::nullopt);
  // First call after the reset: dt = 0, integral 0 -> rudder 0 (it would be 10 + 10·4 otherwise).
  EXPECT_DOUBLE_EQ(pid.step(5.0, nav_at(5.0, 0.0, 0.0), DesiredCommand{5.0, 10.0, 1.0}).rudder_pct,
                   0.0);
}

TEST(MarinePid, InvalidConfigThrows) {
  MarinePidConfig c;
  c.max_rudder_pct = -1.0;
  EXPECT_THROW(MarinePid{c}, std::invalid_argument);
  MarinePidConfig d;
  d.tardy_s = -0.5;
  EXPECT_THROW(MarinePid{d}, std::invalid_argument);
}
