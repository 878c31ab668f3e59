// The M200 driver's protocol logic without a socket: navigation assembled from the frontseat's
// sentences on the local grid, battery, hostile lines counted and survived, the $PYDIR it sends
// from the PID and mixing, and the backseat failsafes (stale commands, stale navigation, all stop).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "support/nmea_sentence.hpp"
#include "vehicle/m200_session.hpp"

namespace {

using namespace avk::vehicle;

constexpr double kLat0 = 42.358456, kLon0 = -71.087589;
// The frontseat's time of day at mission clock 0: a sentence sent at t carries kNoon + t.
constexpr double kNoon = 43200.0;

M200Config config() {
  M200Config c;
  c.datum = {kLat0, kLon0};
  return c;
}

Cpnvg cpnvg_at(double x_m, double y_m, double heading_deg, bool quality = true) {
  const LocalGrid grid(kLat0, kLon0);
  const LatLon p = grid.to_geodetic(x_m, y_m);
  Cpnvg s;
  s.time_s = 43200.0;
  s.lat_deg = p.lat_deg;
  s.lon_deg = p.lon_deg;
  s.position_ok = quality;
  s.heading_deg = heading_deg;
  s.nav_time_s = 43200.0;
  return s;
}

Gprmc gprmc_at(double x_m, double y_m, double speed_mps) {
  const LocalGrid grid(kLat0, kLon0);
  const LatLon p = grid.to_geodetic(x_m, y_m);
  Gprmc s;
  s.time_s = 43200.0;
  s.valid = true;
  s.lat_deg = p.lat_deg;
  s.lon_deg = p.lon_deg;
  s.speed_knots = speed_mps / kMetresPerSecondPerKnot;
  s.course_deg = 0.0;
  s.date = NmeaDate{2026, 11, 23};
  return s;
}

// The sentence as the frontseat sends it at mission time t_s, read at once.
std::string sent_at(Cpnvg s, double t_s) {
  s.time_s = s.nav_time_s = kNoon + t_s;
  return format_cpnvg(s);
}
std::string sent_at(Cpnvr s, double t_s) {
  s.time_s = kNoon + t_s;
  return format_cpnvr(s);
}
std::string sent_at(Gprmc s, double t_s) {
  s.time_s = kNoon + t_s;
  return format_gprmc(s);
}

Pydir sent_pydir(const std::string& line) {
  const auto r = parse_sentence(line, NmeaDirection::backseat_to_frontseat);
  EXPECT_TRUE(r.ok()) << line;
  return r.ok() ? std::get<Pydir>(*r.sentence()) : Pydir{};
}

TEST(M200Session, NavigationOnTheLocalGridWithSpeedAndYawRate) {
  M200Session s(config());
  s.on_connected(0.0);
  s.on_line(sent_at(gprmc_at(30.0, 40.0, 1.2), 9.9), 9.9);
  Cpnvr r;
  r.v_east_mps = 0.6;
  r.v_north_mps = 0.8;
  r.yaw_rate_dps = -4.5;
  s.on_line(sent_at(r, 9.95), 9.95);
  s.on_line(sent_at(cpnvg_at(120.0, -250.0, 33.25), 10.0), 10.0);
  const auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 1u);
  // Stamped with its own time on the mission clock: read at once, that is when it was read.
  EXPECT_DOUBLE_EQ(nav[0].t_s, 10.0);
  // Six decimals of minutes on the wire: about 2 mm.
  EXPECT_NEAR(nav[0].x_m, 120.0, 0.01);
  EXPECT_NEAR(nav[0].y_m, -250.0, 0.01);
  EXPECT_NEAR(nav[0].heading_deg, 33.25, 1e-6);
  EXPECT_NEAR(nav[0].speed_mps, 1.0, 1e-6);  // CPNVR came after GPRMC: the newest wins
  ASSERT_TRUE(nav[0].yaw_rate_dps);
  EXPECT_NEAR(*nav[0].yaw_rate_dps, -4.5, 1e-9);
  ASSERT_TRUE(nav[0].lat_deg && nav[0].lon_deg);
  EXPECT_TRUE(s.take_nav().empty());  // taken once
  EXPECT_EQ(s.link_state(10.5), LinkState::live);
  EXPECT_EQ(s.link_state(12.5), LinkState::stale);
}

TEST(M200Session, WithoutSpeedSentencesATrackJumpIsNoSpeed) {
  M200Session s(config());
  s.on_connected(0.0);
  // No speed sentence: the speed is the track's rate, 1 m/s here.
  s.on_line(sent_at(cpnvg_at(0.0, 0.0, 0.0), 10.0), 10.0);
  s.on_line(sent_at(cpnvg_at(0.0, 1.0, 0.0), 11.0), 11.0);
  // 500 m in a second is a fix jumping after a dropout, not a speed a sample may carry.
  s.on_line(sent_at(cpnvg_at(0.0, 501.0, 0.0), 12.0), 12.0);
  const auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 3u);
  EXPECT_NEAR(nav[1].speed_mps, 1.0, 0.01);
  EXPECT_NEAR(nav[2].y_m, 501.0, 0.01);
  EXPECT_NEAR(nav[2].speed_mps, nav[1].speed_mps, 1e-9);
}

TEST(M200Session, WithoutGpsQualityThePositionComesFromAFreshFix) {
  M200Session s(config());
  s.on_connected(0.0);
  s.on_line(sent_at(gprmc_at(5.0, 6.0, 0.5), 1.0), 1.0);
  s.on_line(sent_at(cpnvg_at(999.0, 999.0, 90.0, false), 1.2), 1.2);
  auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 1u);
  EXPECT_NEAR(nav[0].x_m, 5.0, 0.01);
  EXPECT_NEAR(nav[0].y_m, 6.0, 0.01);
  EXPECT_NEAR(nav[0].speed_mps, 0.5, 1e-6);
  // Two seconds later the fix is too old to pair with a new heading: no sample at all.
  s.on_line(sent_at(cpnvg_at(999.0, 999.0, 90.0, false), 3.2), 3.2);
  EXPECT_TRUE(s.take_nav().empty());
  EXPECT_EQ(s.counters().nav_without_position, 1u);
}

TEST(M200Session, BatteryWithAndWithoutTheBatteryId) {
  M200Session s(config());
  s.on_line(avk::testing::nmea_sentence("CPRBS,120000.000,14.9,3.71,3.76,28.5"), 1.0);
  ASSERT_TRUE(s.battery());
  EXPECT_DOUBLE_EQ(s.battery()->stack_v, 14.9);
  Cprbs b;
  b.battery_id = 2;
  b.stack_v = 13.2;
  b.min_v = 3.3;
  b.max_v = 3.4;
  b.temperature_c = 30;
  b.time_s = kNoon + 1.0;
  s.on_line(format_cprbs(b), 2.0);
  EXPECT_DOUBLE_EQ(s.battery()->stack_v, 13.2);
  EXPECT_DOUBLE_EQ(s.battery()->t_s, 2.0);
}

TEST(M200Session, HostileLinesAreCountedByKindAndNeverThrow) {
  M200Session s(config());
  s.on_connected(0.0);
  std::string good = format_cpnvg(cpnvg_at(1, 2, 3));
  std::string bad_sum = good;
  bad_sum[bad_sum.size() - 3] = bad_sum[bad_sum.size() - 3] == 'A' ? 'B' : 'A';
  s.on_line(bad_sum, 1.0);
  s.on_line("$CPNVG,1,2,3*00", 1.0);
  s.on_line(std::string(5000, 'x'), 1.0);
  s.on_line("", 1.0);
  std::mt19937 rng(7);
  for (int i = 0; i < 20000; ++i) {
    std::string line = good;
    for (int k = 0; k < 3; ++k)
      line[rng() % line.size()] = static_cast<char>(rng() % 256);
    ASSERT_NO_THROW(s.on_line(line, 1.0 + i * 1e-4));
  }
  EXPECT_GE(s.counters().errors, 4u);
  EXPECT_GE(s.counters().errors_by_code.at("bad_checksum"), 1u);
  EXPECT_GE(s.counters().errors_by_code.at("oversized"), 1u);
  EXPECT_FALSE(s.counters().last_error.empty());
  // Nothing that failed to parse became navigation with a wild position.
  for (const auto& n : s.take_nav())
    EXPECT_LT(std::hypot(n.x_m, n.y_m), 1e6);
}

TEST(M200Session, SendsNothingWhileDisconnected) {
  M200Session s(config());
  EXPECT_EQ(s.control_tick(0.0), "");
  EXPECT_EQ(s.link_state(0.0), LinkState::disconnected);
}

TEST(M200Session, PidAndMixingTurnTowardTheDesiredHeading) {
  M200Session s(config());
  s.on_connected(0.0);
  EXPECT_EQ(sent_pydir(s.control_tick(0.1)), (Pydir{0, 0}));
  EXPECT_EQ(s.failsafe(), Failsafe::no_command);
  s.on_line(sent_at(cpnvg_at(0, 0, 10.0), 0.2), 0.2);
  s.command({0.2, 60.0, 1.0});  // to starboard
  const Pydir p = sent_pydir(s.control_tick(0.3));
  EXPECT_EQ(s.failsafe(), Failsafe::none);
  EXPECT_GT(p.left_pct, p.right_pct);  // left pushes harder: the bow swings to starboard
  EXPECT_GT(p.left_pct + p.right_pct, 0.0);
  ASSERT_TRUE(s.last_actuators() && s.last_actuators()->left_pct);
  EXPECT_NEAR(*s.last_actuators()->left_pct, p.left_pct, 1e-6);
  // And to port, across north.
  s.on_line(sent_at(cpnvg_at(0, 0, 10.0), 0.4), 0.4);
  s.command({0.4, 330.0, 1.0});
  const Pydir q = sent_pydir(s.control_tick(0.5));
  EXPECT_LT(q.left_pct, q.right_pct);
}

TEST(M200Session, AllStopWhenCommandsOrNavigationGoStale) {
  M200Session s(config());
  s.on_connected(0.0);
  s.on_line(sent_at(cpnvg_at(0, 0, 0), 1.0), 1.0);
  s.command({1.0, 0.0, 1.0});
  EXPECT_NE(sent_pydir(s.control_tick(1.1)), (Pydir{0, 0}));
  // The helm went quiet for more than 1.5 s while navigation kept coming.
  s.on_line(sent_at(cpnvg_at(0, 0, 0), 2.4), 2.4);
  EXPECT_NE(sent_pydir(s.control_tick(2.45)), (Pydir{0, 0}));
  s.on_line(sent_at(cpnvg_at(0, 0, 0), 2.6), 2.6);
  EXPECT_EQ(sent_pydir(s.control_tick(2.6)), (Pydir{0, 0}));
  EXPECT_EQ(s.failsafe(), Failsafe::command_stale);
  EXPECT_EQ(s.counters().failsafe_stops, 1u);
  // Commands again, but navigation stops arriving.
  s.command({2.7, 0.0, 1.0});
  EXPECT_NE(sent_pydir(s.control_tick(2.7)), (Pydir{0, 0}));
  s.command({4.0, 0.0, 1.0});
  EXPECT_NE(sent_pydir(s.control_tick(4.0)), (Pydir{0, 0}));  // nav 1.4 s old
  s.command({4.2, 0.0, 1.0});
  EXPECT_EQ(sent_pydir(s.control_tick(4.2)), (Pydir{0, 0}));  // nav 1.6 s old
  EXPECT_EQ(s.failsafe(), Failsafe::nav_stale);
  EXPECT_EQ(s.counters().failsafe_stops, 2u);
  // all_stop holds until the next command.
  s.on_line(sent_at(cpnvg_at(0, 0, 0), 4.3), 4.3);
  s.all_stop(4.3);
  EXPECT_EQ(sent_pydir(s.control_tick(4.35)), (Pydir{0, 0}));
  EXPECT_EQ(s.failsafe(), Failsafe::stopped);
  s.command({4.4, 0.0, 1.0});
  EXPECT_NE(sent_pydir(s.control_tick(4.45)), (Pydir{0, 0}));
}

TEST(M200Session, ADroppedLinkIsDisconnectedAndForgetsPartialState) {
  M200Session s(config());
  s.on_connected(0.0);
  s.on_line(sent_at(gprmc_at(5.0, 6.0, 0.5), 1.0), 1.0);
  s.on_line(sent_at(cpnvg_at(5, 6, 0), 1.0), 1.0);
  EXPECT_EQ(s.link_state(1.1), LinkState::live);
  s.on_disconnected(1.2);
  EXPECT_EQ(s.link_state(1.2), LinkState::disconnected);
  EXPECT_EQ(s.control_tick(1.3), "");
  s.on_connected(2.0);
  EXPECT_EQ(s.counters().connects, 2u);
  EXPECT_EQ(s.counters().disconnects, 1u);
  // The fix from the old link is not paired with the new link's first heading.
  s.on_line(sent_at(cpnvg_at(0, 0, 0, false), 2.1), 2.1);
  s.take_nav();
  EXPECT_EQ(s.counters().nav_without_position, 1u);
}

TEST(M200Session, RejectsCommandsThatAreNotFinite) {
  M200Session s(config());
  EXPECT_THROW(s.command({0.0, NAN, 1.0}), std::invalid_argument);
  EXPECT_THROW(s.command({0.0, 10.0, -1.0}), std::invalid_argument);
  s.command({0.0, -30.0, 1.0});
  EXPECT_NEAR(s.last_command()->heading_deg, 330.0, 1e-9);
}

}  // namespace
