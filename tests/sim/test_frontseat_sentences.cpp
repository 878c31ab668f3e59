// The frontseat emulator over real sockets, fault-free: every sentence at its rate and well formed,
// $PYDIR driving the plant, the watchdog, and what it refuses to run; at 10x real time.
#include <gtest/gtest.h>

#include "sim/frontseat_link.hpp"

using namespace avk::testing::frontseat_link;

TEST(FrontseatEmulator, SendsEverySentenceAtItsRateWellFormed) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  o.start_x_m = 25.0;
  o.start_y_m = -40.0;
  o.start_heading_deg = 30.0;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 12.5));

  // Ticks fall on the plant's grid (k / 20 s): windows start half a period off it.
  const double from = 1.9, to = 11.9;
  auto n = count_in_window(c.lines(), o, from, to);
  const double span = to - from;
  std::cout << "rates over " << span << " s of emulator clock: CPNVG " << n["CPNVG"] / span
            << " Hz, CPNVR " << n["CPNVR"] / span << " Hz, GPRMC " << n["GPRMC"] / span
            << " Hz, CPRBS " << n["CPRBS"] / span << " Hz\n";
  EXPECT_NEAR(n["CPNVG"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["CPNVR"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["GPRMC"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["CPRBS"], o.battery_hz * span, 1.0);
  EXPECT_EQ(n["other"], 0);

  const veh::LocalGrid grid(o.datum.lat_deg, o.datum.lon_deg);
  int positions = 0;
  for (const auto& r : c.lines()) {
    ASSERT_GE(r.line.size(), 2u);
    EXPECT_EQ(r.line.substr(r.line.size() - 2), "\r\n") << r.line;
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok()) << r.line << ": " << p.error()->message;
    EXPECT_EQ(p.checksum, veh::NmeaChecksum::upper_case) << r.line;
    if (const auto* nvg = std::get_if<veh::Cpnvg>(p.sentence())) {
      const veh::GridPoint g = grid.to_grid(nvg->lat_deg, nvg->lon_deg);
      EXPECT_NEAR(g.x_m, o.start_x_m, 2.0) << r.line;
      EXPECT_NEAR(g.y_m, o.start_y_m, 2.0) << r.line;
      EXPECT_NEAR(kin::angle180_deg(nvg->heading_deg - o.start_heading_deg), 0.0, 6.0);
      EXPECT_TRUE(nvg->position_ok);
      EXPECT_FALSE(nvg->altitude_m.has_value());
      EXPECT_FALSE(nvg->depth_m.has_value());
      EXPECT_DOUBLE_EQ(nvg->nav_time_s, nvg->time_s);
      ++positions;
    } else if (const auto* rmc = std::get_if<veh::Gprmc>(p.sentence())) {
      EXPECT_TRUE(rmc->valid);
      ASSERT_TRUE(rmc->lat_deg && rmc->lon_deg && rmc->speed_knots && rmc->date);
      const veh::GridPoint g = grid.to_grid(*rmc->lat_deg, *rmc->lon_deg);
      EXPECT_NEAR(g.x_m, o.start_x_m, 2.0);
      EXPECT_NEAR(g.y_m, o.start_y_m, 2.0);
      EXPECT_NEAR(*rmc->speed_knots, 0.0, 0.01);
    } else if (const auto* bs = std::get_if<veh::Cprbs>(p.sentence())) {
      EXPECT_NEAR(bs->stack_v, o.battery_v, 0.01);  // no thrust, no sag
      EXPECT_LT(bs->min_v, bs->max_v);
      EXPECT_NEAR(bs->max_v, o.battery_v / 4.0, 0.1);
      EXPECT_NEAR(bs->temperature_c, 25.0, 1.0);
    }
  }
  EXPECT_GE(positions, 50);
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.connections, 1u);
  EXPECT_EQ(s.clients, 1u);
  EXPECT_EQ(s.watchdog_trips, 0u);  // never commanded: idle motors are not a trip
  EXPECT_FALSE(s.last_pydir_s.has_value());
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_EQ(s.right_pct, 0.0);
  EXPECT_GE(s.sentences_sent, 3u * 60u);
}

TEST(FrontseatEmulator, PydirDrivesForwardAndLeftOverRightTurnsToStarboard) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  o.start_heading_deg = 90.0;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  Repeater forward{c, veh::format_pydir(60, 60), 0.1};
  ASSERT_TRUE(run_until_clock(emu, {&c}, 6.0, [&] { forward(emu.now_s()); }));
  FrontseatStatus s = emu.status();
  EXPECT_EQ(s.left_pct, 60.0);
  EXPECT_EQ(s.right_pct, 60.0);
  EXPECT_GT(s.truth.speed_over_ground_mps, 0.3);
  EXPECT_GT(s.truth.x_m, 1.0);  // heading 90: east
  EXPECT_NEAR(s.truth.y_m, 0.0, 0.5);
  EXPECT_EQ(s.watchdog_trips, 0u);
  // What it says on the wire agrees: the newest CPNVR moves east.
  veh::Cpnvr last_nvr;
  for (const auto& r : c.lines())
    if (const auto p = parse_fs(r.line); p.ok())
      if (const auto* v = std::get_if<veh::Cpnvr>(p.sentence())) last_nvr = *v;
  EXPECT_GT(last_nvr.v_east_mps, 0.3);

  Repeater turn{c, veh::format_pydir(60, -60), 0.1};
  double previous = s.truth.heading_deg, turned = 0.0, max_rate = 0.0;
  ASSERT_TRUE(run_until_clock(emu, {&c}, 8.0, [&] {
    turn(emu.now_s());
    const FrontseatStatus now = emu.status();
    turned += kin::angle180_deg(now.truth.heading_deg - previous);
    previous = now.truth.heading_deg;
    max_rate = std::max(max_rate, now.truth.yaw_rate_dps);
  }));
  std::cout << "60/-60 for 2 s: heading changed " << turned << " deg, yaw rate up to " << max_rate
            << " deg/s\n";
  // Clockwise: the heading increases. The M200's jets at ±60 % give about 11 N of differential
  // thrust (8 N ahead, 2.8 N through the reversing bucket), so 2 s turn it some 12°.
  EXPECT_GT(turned, 8.0);
  EXPECT_GT(max_rate, 6.0);
  EXPECT_EQ(emu.status().left_pct, 60.0);
  EXPECT_EQ(emu.status().right_pct, -60.0);
}

TEST(FrontseatEmulator, WatchdogZeroesTheMotorsOncePerSilence) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 2.0));
  EXPECT_EQ(emu.status().watchdog_trips, 0u);

  // Commands for a second, then silence.
  Repeater drive{c, veh::format_pydir(50, 50), 0.1};
  bool saw_drive = false;
  ASSERT_TRUE(run_until_clock(emu, {&c}, 3.0, [&] {
    drive(emu.now_s());
    saw_drive = saw_drive || emu.status().left_pct == 50.0;
  }));
  ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().watchdog_trips >= 1; }));
  FrontseatStatus s = emu.status();
  EXPECT_TRUE(saw_drive);
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_EQ(s.right_pct, 0.0);
  ASSERT_TRUE(s.last_pydir_s && s.last_watchdog_trip_s);
  const double first_trip = *s.last_watchdog_trip_s;
  std::cout << "watchdog tripped " << first_trip - *s.last_pydir_s << " s after the last $PYDIR\n";
  EXPECT_GE(first_trip - *s.last_pydir_s, o.watchdog_s);
  EXPECT_LE(first_trip - *s.last_pydir_s, o.watchdog_s + 0.1);
  // Staying silent does not trip it again.
  ASSERT_TRUE(run_until_clock(emu, {&c}, first_trip + 2.5));
  EXPECT_EQ(emu.status().watchdog_trips, 1u);
  EXPECT_EQ(*emu.status().last_watchdog_trip_s, first_trip);

  // A $PYDIR with a bad checksum is not a command: it neither drives nor feeds the watchdog.
  ASSERT_TRUE(c.send(veh::format_pydir(30, 30)));
  ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().left_pct == 30.0; }));
  const double fed_at = *emu.status().last_pydir_s;
  const std::uint64_t bad_before = emu.status().bad_lines_received;
  Repeater bad{c, with_bad_checksum(veh::format_pydir(20, 20)), 0.1};
  bool obeyed_bad = false;
  ASSERT_TRUE(run_until(
      emu, {&c}, [&] { return emu.status().watchdog_trips >= 2; },
      [&] {
        bad(emu.now_s());
        obeyed_bad = obeyed_bad || emu.status().left_pct == 20.0;
      }));
  s = emu.status();
  EXPECT_FALSE(obeyed_bad);
  EXPECT_EQ(s.watchdog_trips, 2u);
  EXPECT_EQ(*s.last_pydir_s, fed_at);
  EXPECT_GE(*s.last_watchdog_trip_s - fed_at, o.watchdog_s);
  EXPECT_LE(*s.last_watchdog_trip_s - fed_at, o.watchdog_s + 0.1);
  EXPECT_GE(s.bad_lines_received - bad_before, 5u);
  // All but the last few sent, which may still be on their way.
  EXPECT_GE(static_cast<int>(s.bad_lines_received - bad_before), bad.sent - 3);

  // Older backseats leave the checksum out, or its digits: both are commands.
  std::uint64_t trips = 2;
  for (const std::string line : {"$PYDIR,10,10\r\n", "$PYDIR,10,10*\r\n"}) {
    ASSERT_TRUE(c.send(line));
    ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().left_pct == 10.0; })) << line;
    ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().watchdog_trips > trips; })) << line;
    s = emu.status();
    ++trips;
    EXPECT_EQ(s.watchdog_trips, trips) << line;
    EXPECT_EQ(s.left_pct, 0.0);
    EXPECT_GE(*s.last_watchdog_trip_s - *s.last_pydir_s, o.watchdog_s) << line;
    EXPECT_LE(*s.last_watchdog_trip_s - *s.last_pydir_s, o.watchdog_s + 0.1) << line;
  }
}

TEST(FrontseatEmulator, RefusesWhatItCannotRun) {
  FrontseatEmulator first(fast_options(10.0));
  FrontseatEmulatorOptions same = fast_options(10.0);
  same.port = first.port();
  try {
    FrontseatEmulator second(same);
    FAIL() << "bound a port already listened on";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(first.port())),
              std::string::npos)
        << e.what();
  }
  FrontseatEmulatorOptions usim = fast_options(10.0);
  usim.vehicle = avk::sim::sim_vehicle_defaults("usim");
  EXPECT_THROW(FrontseatEmulator{usim}, std::invalid_argument);
  FrontseatEmulatorOptions bad_faults = fast_options(10.0);
  bad_faults.faults.drop_fraction = 1.5;
  EXPECT_THROW(FrontseatEmulator{bad_faults}, std::invalid_argument);
  EXPECT_THROW(first.set_faults(FrontseatFaults{0.0, -0.1, 0.0}), std::invalid_argument);

  // stop() twice, then the destructor: all fine, and the port is free again.
  first.stop();
  first.stop();
  FrontseatEmulator third(same);
  EXPECT_EQ(third.port(), same.port);
}
