// The frontseat protocol's formatters: exact text, refusing what the parser would, and round trips
// through the parser for every type and for random values.
#include <gtest/gtest.h>

#include "vehicle/nmea_lines.hpp"

namespace {

using namespace avk::testing::nmea_lines;

// ---- Formatting -----------------------------------------------------------------------------

TEST(NmeaFormat, PydirExactText) {
  EXPECT_EQ(format_pydir(12.5, -100.0), sentence("PYDIR,12.5,-100"));
  EXPECT_EQ(format_pydir(0.0, 0.0), "$PYDIR,0,0*56\r\n");
  EXPECT_EQ(format_pydir(1.0 / 3.0, -2.0 / 3.0), sentence("PYDIR,0.333333,-0.666667"));
  EXPECT_EQ(format_pydir(-0.0000001, 99.99999999), sentence("PYDIR,0,100"));
  EXPECT_EQ(format_pydir(10.100, 50.0), sentence("PYDIR,10.1,50"));
}

TEST(NmeaFormat, RejectsWhatTheParserWould) {
  EXPECT_THROW(format_pydir(100.5, 0.0), std::invalid_argument);
  EXPECT_THROW(format_pydir(std::nan(""), 0.0), std::invalid_argument);
  EXPECT_THROW(format_pydir(0.0, HUGE_VAL), std::invalid_argument);
  try {
    format_pydir(0.0, -150.0);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("right thrust"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("format_pydir"), std::string::npos) << e.what();
  }
  Cpnvg bad_lat;
  bad_lat.lat_deg = 91.0;
  EXPECT_THROW(format_cpnvg(bad_lat), std::invalid_argument);
  Cpnvg bad_heading;
  bad_heading.heading_deg = -5.0;
  EXPECT_THROW(format_cpnvg(bad_heading), std::invalid_argument);
  Cpnvg bad_time;
  bad_time.time_s = -1.0;
  EXPECT_THROW(format_cpnvg(bad_time), std::invalid_argument);
  Cprbs bad_voltage;
  bad_voltage.stack_v = 1e300;
  EXPECT_THROW(format_cprbs(bad_voltage), std::invalid_argument);
  Gprmc bad_talker;
  bad_talker.talker = "XX";
  EXPECT_THROW(format_gprmc(bad_talker), std::invalid_argument);
  Gprmc half_position;
  half_position.lat_deg = 42.0;
  EXPECT_THROW(format_gprmc(half_position), std::invalid_argument);
  EXPECT_THROW(format_sentence(UnknownSentence{"GPGSV", {"1,2"}}), std::invalid_argument);
  EXPECT_THROW(format_sentence(UnknownSentence{"gpgsv", {}}), std::invalid_argument);
}

TEST(NmeaFormat, WritesTheFrontseatsOwnText) {
  // Each real sentence, parsed and written again, is the same bytes (the frontseat's layout:
  // six decimals at most, unpadded CPNVG longitude).
  for (const char* line : {kRealCpnvg, kRealCpnvr, kRealCprbs, kRealCpimu}) {
    const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(format_sentence(*r.sentence()), std::string(line) + "\r\n");
  }
  EXPECT_EQ(format_cpnvg(parse_as<Cpnvg>(kRealCpnvg)), std::string(kRealCpnvg) + "\r\n");
  // GPS sentences zero-pad the longitude, as receivers do.
  Gprmc rmc = parse_as<Gprmc>(kRealGprmc);
  EXPECT_EQ(format_gprmc(rmc),
            sentence("GPRMC,164959,A,4221.71114,N,07105.44878,W,0.145,156.78,311214,,,A"));
  // Every parsed real sentence reads back equal.
  for (const char* line : kRealLines) {
    const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(parse_any(format_sentence(*r.sentence())), *r.sentence()) << line;
  }
}

TEST(NmeaFormat, CoordinatesAndTimesCarry) {
  Cpnvg s;
  s.lat_deg = 42.999999999999;  // 42 deg 59.99999999994 min: rounds to 43 deg 00 min
  s.lon_deg = -0.5;
  s.time_s = 86399.9999999;          // rounds to midnight
  s.nav_time_s = 86400.0 + 3661.25;  // times past midnight wrap
  s.heading_deg = 359.9999999;
  const std::string line = format_cpnvg(s);
  EXPECT_EQ(line, sentence("CPNVG,000000,4300,N,030,W,0,,,0,0,0,010101.25")) << line;
  Cpnvg south;
  south.lat_deg = -5.5;
  south.lon_deg = 179.25;
  EXPECT_NE(format_cpnvg(south).find(",0530,S,17915,E,"), std::string::npos);
}

TEST(NmeaFormat, CprbsWithAndWithoutBatteryId) {
  Cprbs s{hms(1, 2, 3.5), std::nullopt, 15.25, 15.0, 15.5, 21.0};
  EXPECT_EQ(format_cprbs(s), sentence("CPRBS,010203.5,15.25,15,15.5,21"));
  s.battery_id = 3;
  EXPECT_EQ(format_cprbs(s), sentence("CPRBS,010203.5,3,15.25,15,15.5,21"));
  EXPECT_EQ(parse_as<Cprbs>(format_cprbs(s)), s);
}

// parse(format(x)) == x to the six decimals written, for random values over each type's range.
TEST(NmeaFormat, RandomRoundTrips) {
  std::mt19937_64 rng(20240608);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution(lo, hi)(rng); };
  auto coin = [&] { return std::bernoulli_distribution(0.5)(rng); };
  constexpr double kValue = 5.0000001e-7;  // half the last decimal, and a little
  constexpr double kTime = 5.0000001e-7;
  constexpr double kAngle = 0.5e-6 / 60.0 + 1e-12;  // half a millionth of a minute
  for (int i = 0; i < 2000; ++i) {
    Cpnvg g;
    g.time_s = uniform(0.0, 86400.0 - 1e-6);
    g.lat_deg = uniform(-90.0, 90.0);
    g.lon_deg = uniform(-180.0, 180.0);
    g.position_ok = coin();
    if (coin()) g.altitude_m = uniform(0.0, 100.0);
    if (coin()) g.depth_m = uniform(0.0, 100.0);
    g.heading_deg = uniform(0.0, 359.999);
    g.roll_deg = uniform(-180.0, 180.0);
    g.pitch_deg = uniform(-90.0, 90.0);
    g.nav_time_s = uniform(0.0, 86400.0 - 1e-6);
    const Cpnvg g2 = parse_as<Cpnvg>(format_cpnvg(g));
    EXPECT_NEAR(g2.time_s, g.time_s, kTime);
    EXPECT_NEAR(g2.lat_deg, g.lat_deg, kAngle);
    EXPECT_NEAR(g2.lon_deg, g.lon_deg, kAngle);
    EXPECT_EQ(g2.position_ok, g.position_ok);
    EXPECT_EQ(g2.altitude_m.has_value(), g.altitude_m.has_value());
    if (g.altitude_m) {
      EXPECT_NEAR(*g2.altitude_m, *g.altitude_m, kValue);
    }
    EXPECT_EQ(g2.depth_m.has_value(), g.depth_m.has_value());
    if (g.depth_m) {
      EXPECT_NEAR(*g2.depth_m, *g.depth_m, kValue);
    }
    EXPECT_NEAR(g2.heading_deg, g.heading_deg, kValue);
    EXPECT_NEAR(g2.roll_deg, g.roll_deg, kValue);
    EXPECT_NEAR(g2.pitch_deg, g.pitch_deg, kValue);
    EXPECT_NEAR(g2.nav_time_s, g.nav_time_s, kTime);
    // Once written, the text is a fixed point.
    EXPECT_EQ(format_cpnvg(g2), format_cpnvg(g));

    // Horizontal components within ±70 m/s: together under the 100 m/s a speed may be.
    Cpnvr r{uniform(0.0, 86399.0),   uniform(-70.0, 70.0),     uniform(-70.0, 70.0),
            uniform(-100.0, 100.0),  uniform(-5000.0, 5000.0), uniform(-5000.0, 5000.0),
            uniform(-5000.0, 5000.0)};
    const Cpnvr r2 = parse_as<Cpnvr>(format_cpnvr(r));
    EXPECT_NEAR(r2.v_east_mps, r.v_east_mps, kValue);
    EXPECT_NEAR(r2.v_north_mps, r.v_north_mps, kValue);
    EXPECT_NEAR(r2.v_down_mps, r.v_down_mps, kValue);
    EXPECT_NEAR(r2.pitch_rate_dps, r.pitch_rate_dps, kValue);
    EXPECT_NEAR(r2.roll_rate_dps, r.roll_rate_dps, kValue);
    EXPECT_NEAR(r2.yaw_rate_dps, r.yaw_rate_dps, kValue);

    Cprbs b{uniform(0.0, 86399.0), std::nullopt,       uniform(0.0, 60.0),
            uniform(0.0, 60.0),    uniform(0.0, 60.0), uniform(-40.0, 80.0)};
    if (coin()) b.battery_id = static_cast<int>(uniform(0.0, 999.0));
    const Cprbs b2 = parse_as<Cprbs>(format_cprbs(b));
    EXPECT_EQ(b2.battery_id, b.battery_id);
    EXPECT_NEAR(b2.stack_v, b.stack_v, kValue);
    EXPECT_NEAR(b2.min_v, b.min_v, kValue);
    EXPECT_NEAR(b2.max_v, b.max_v, kValue);
    EXPECT_NEAR(b2.temperature_c, b.temperature_c, kValue);

    Gprmc m;
    m.talker = coin() ? "GP" : "GN";
    m.time_s = uniform(0.0, 86399.0);
    m.valid = coin();
    m.lat_deg = uniform(-90.0, 90.0);
    m.lon_deg = uniform(-180.0, 180.0);
    m.speed_knots = uniform(0.0, 20.0);
    m.course_deg = uniform(0.0, 359.0);
    m.date = NmeaDate{2000 + static_cast<int>(uniform(0.0, 79.0)), 1 + i % 12, 1 + i % 28};
    if (coin()) m.magnetic_variation_deg = uniform(-30.0, 30.0);
    if (coin()) m.mode = 'D';
    const Gprmc m2 = parse_as<Gprmc>(format_gprmc(m));
    EXPECT_EQ(m2.talker, m.talker);
    EXPECT_NEAR(*m2.time_s, *m.time_s, kTime);
    EXPECT_EQ(m2.valid, m.valid);
    EXPECT_NEAR(*m2.lat_deg, *m.lat_deg, kAngle);
    EXPECT_NEAR(*m2.lon_deg, *m.lon_deg, kAngle);
    EXPECT_NEAR(*m2.speed_knots, *m.speed_knots, kValue);
    EXPECT_NEAR(*m2.speed_mps(), *m.speed_mps(), kValue);
    EXPECT_NEAR(*m2.course_deg, *m.course_deg, kValue);
    EXPECT_EQ(m2.date, m.date);
    EXPECT_EQ(m2.magnetic_variation_deg.has_value(), m.magnetic_variation_deg.has_value());
    if (m.magnetic_variation_deg) {
      EXPECT_NEAR(*m2.magnetic_variation_deg, *m.magnetic_variation_deg, kValue);
    }
    EXPECT_EQ(m2.mode, m.mode);

    const double left = uniform(-100.0, 100.0);
    const double right = uniform(-100.0, 100.0);
    const Pydir d = parse_as<Pydir>(format_pydir(left, right), kToFrontseat);
    EXPECT_NEAR(d.left_pct, left, kValue);
    EXPECT_NEAR(d.right_pct, right, kValue);
  }
}

TEST(NmeaFormat, EveryTypeReadsBackEqual) {
  Gpgga gga;
  gga.talker = "GN";
  gga.time_s = hms(16, 49, 59);
  gga.lat_deg = 42.5;
  gga.lon_deg = -71.25;
  gga.quality = 2;
  gga.satellites = 10;
  gga.hdop = 0.84;
  gga.altitude_m = 19.5;
  gga.geoid_separation_m = -33.2;
  gga.dgps_age_s = 1.5;
  gga.dgps_station = 17;
  Gpvtg vtg{"GP", 156.78, 170.5, 0.145, 0.269, 'A'};
  Gprmc status_only;
  status_only.nav_status = 'S';
  const NmeaSentence all[] = {
      Cpnvg{},
      Cpnvr{1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0},
      Cprbs{3.0, 7, 14.0, 13.5, 14.5, 20.0},
      Cprcm{1.0, 3, 359.5, -10.0, 20.0, 0.5},
      Cpimu{1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0},
      Cpalt{1.0, 1.0},
      Gprmc{},
      status_only,
      gga,
      Gpgga{},
      vtg,
      Gpvtg{},
      Pydir{-50.0, 50.0},
      Pydev{90.0, 1.5},
      Pydep{-10.0, 40.0},
      Pyclt{true},
      UnknownSentence{"CPTIME", {"120000", ""}},
      UnknownSentence{"GPGSV", {}},
  };
  for (const NmeaSentence& s : all) {
    const std::string line = format_sentence(s);
    EXPECT_EQ(line.substr(line.size() - 5, 1), "*") << line;
    EXPECT_EQ(parse_any(line), s) << line;
  }
}

}  // namespace
