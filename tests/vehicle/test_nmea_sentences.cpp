// Every sentence type the frontseat protocol parser reads: real M200 output, frontseat, GPS and
// backseat sentences, and their malformed variants (field count, numbers, ranges).
#include <gtest/gtest.h>

#include "vehicle/nmea_lines.hpp"

namespace {

using namespace avk::testing::nmea_lines;

// ---- Frontseat sentences --------------------------------------------------------------------

TEST(NmeaCpnvg, ParsesTheRealSentence) {
  const Cpnvg s = parse_as<Cpnvg>(kRealCpnvg);
  EXPECT_NEAR(s.time_s, hms(16, 49, 59.034), 1e-9);
  EXPECT_NEAR(s.lat_deg, 42.0 + 21.711142 / 60.0, 1e-12);
  // Longitude not zero-padded: 7105.44878 is 71 degrees 05.44878 minutes.
  EXPECT_NEAR(s.lon_deg, -(71.0 + 5.44878 / 60.0), 1e-12);
  EXPECT_TRUE(s.position_ok);
  EXPECT_EQ(s.altitude_m, 0.0);
  EXPECT_EQ(s.depth_m, 0.0);
  EXPECT_DOUBLE_EQ(s.heading_deg, 234.32964);
  EXPECT_DOUBLE_EQ(s.roll_deg, -6.796959);
  EXPECT_DOUBLE_EQ(s.pitch_deg, -1.706798);
  EXPECT_NEAR(s.nav_time_s, hms(16, 49, 59.006), 1e-9);
}

TEST(NmeaCpnvg, BlankOptionalFields) {
  // A surface vehicle blanks altitude and depth; a blank nav timestamp means the sentence's time.
  const Cpnvg s = parse_as<Cpnvg>(sentence("CPNVG,120000.5,0530.25,S,00012.5,E,0,,,0,0,0,"));
  EXPECT_FALSE(s.altitude_m);
  EXPECT_FALSE(s.depth_m);
  EXPECT_FALSE(s.position_ok);
  EXPECT_DOUBLE_EQ(s.nav_time_s, hms(12, 0, 0.5));
  EXPECT_NEAR(s.lat_deg, -(5.0 + 30.25 / 60.0), 1e-12);
  EXPECT_NEAR(s.lon_deg, 12.5 / 60.0, 1e-12);
  // The required ones may not be blank.
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,,0,0,"), Code::missing_field, 9,
               "heading");
  expect_error(sentence("CPNVG,,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::missing_field, 1, "time");
  expect_error(sentence("CPNVG,120000,,N,7105.4,W,1,,,10,0,0,"), Code::missing_field, 2,
               "latitude");
  expect_error(sentence("CPNVG,120000,4221.7,N,,W,1,,,10,0,0,"), Code::missing_field, 4,
               "longitude");
  expect_error(sentence("CPNVG,120000,4221.7,,7105.4,W,1,,,10,0,0,"), Code::missing_field, 3,
               "hemisphere");
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,,,,10,0,0,"), Code::missing_field, 6,
               "quality");
}

TEST(NmeaCpnvg, MalformedVariants) {
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,10,0,0"), Code::bad_field_count, 0,
               "11 fields, expected 12");
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,10,0,0,,"), Code::bad_field_count, 0);
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,1O,0,0,"), Code::non_numeric, 9,
               "heading");
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,360.5,0,0,"), Code::out_of_range, 9,
               "heading");
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,-0.1,0,0,"), Code::out_of_range, 9);
  expect_error(sentence("CPNVG,120000,9100.0,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 2,
               "latitude");
  expect_error(sentence("CPNVG,120000,9000.01,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 2);
  expect_error(sentence("CPNVG,120000,4260.0,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 2,
               "minutes");
  expect_error(sentence("CPNVG,120000,4221.7,N,18000.5,W,1,,,10,0,0,"), Code::out_of_range, 4,
               "longitude");
  expect_error(sentence("CPNVG,120000,-4221.7,N,7105.4,W,1,,,10,0,0,"), Code::bad_value, 2,
               "hemisphere");
  expect_error(sentence("CPNVG,120000,4221.7,X,7105.4,W,1,,,10,0,0,"), Code::bad_value, 3);
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,N,1,,,10,0,0,"), Code::bad_value, 5);
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,2,,,10,0,0,"), Code::bad_value, 6);
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,10,180.5,0,"), Code::out_of_range, 10,
               "roll");
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,10,0,-90.5,"), Code::out_of_range, 11,
               "pitch");
  expect_error(sentence("CPNVG,240000,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 1,
               "time");
  expect_error(sentence("CPNVG,126000,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 1);
  expect_error(sentence("CPNVG,12000,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::bad_value, 1);
  expect_error(sentence("CPNVG,12:00:00,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::non_numeric, 1);
  expect_error(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,10,0,0,12000x"), Code::non_numeric, 12,
               "nav timestamp");
}

TEST(NmeaCpnvg, HeadingOf360IsNorth) {
  // What a frontseat writes for 359.9999997 rounded to six decimals.
  EXPECT_EQ(parse_as<Cpnvg>(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,360,0,0,")).heading_deg,
            0.0);
  EXPECT_EQ(
      parse_as<Cpnvg>(sentence("CPNVG,120000,4221.7,N,7105.4,W,1,,,359.9999999,0,0,")).heading_deg,
      359.9999999);
}

TEST(NmeaCpnvg, LeapSecond) {
  EXPECT_DOUBLE_EQ(parse_as<Cpnvg>(sentence("CPNVG,235960.5,4221.7,N,7105.4,W,1,,,10,0,0,")).time_s,
                   86400.5);
  expect_error(sentence("CPNVG,235961,4221.7,N,7105.4,W,1,,,10,0,0,"), Code::out_of_range, 1);
}

TEST(NmeaCpnvr, ParsesAndChecks) {
  const Cpnvr s = parse_as<Cpnvr>(kRealCpnvr);
  EXPECT_NEAR(s.time_s, hms(16, 49, 59.063), 1e-9);
  EXPECT_DOUBLE_EQ(s.v_east_mps, 0.02941);
  EXPECT_DOUBLE_EQ(s.v_north_mps, -0.068552);
  EXPECT_DOUBLE_EQ(s.v_down_mps, 0.0);
  EXPECT_DOUBLE_EQ(s.pitch_rate_dps, 0.060938);
  EXPECT_DOUBLE_EQ(s.roll_rate_dps, 0.0);
  EXPECT_DOUBLE_EQ(s.yaw_rate_dps, -0.061132);
  expect_error(sentence("CPNVR,120000,1,2,3,4,5"), Code::bad_field_count, 0);
  expect_error(sentence("CPNVR,120000,1,2,3,4,5,"), Code::missing_field, 7, "yaw rate");
  expect_error(sentence("CPNVR,120000,1,2,3,4,5,+"), Code::non_numeric, 7);
  expect_error(sentence("CPNVR,120000,101,2,3,4,5,6"), Code::out_of_range, 2, "v east");
  expect_error(sentence("CPNVR,120000,1,2,3,4,5,-5001"), Code::out_of_range, 7);
  EXPECT_DOUBLE_EQ(parse_as<Cpnvr>(sentence("CPNVR,120000,+1.5,-.5,3.,0,0,0")).v_east_mps, 1.5);
  // Components within ±100 m/s can still make a horizontal speed that no sample may carry.
  expect_error(sentence("CPNVR,120000,80,80,0,0,0,0"), Code::out_of_range, 2, "horizontal speed");
  EXPECT_DOUBLE_EQ(parse_as<Cpnvr>(sentence("CPNVR,120000,60,80,0,0,0,0")).v_north_mps, 80.0);
}

TEST(NmeaCprbs, WithAndWithoutBatteryId) {
  const Cprbs plain = parse_as<Cprbs>(kRealCprbs);
  EXPECT_FALSE(plain.battery_id);
  EXPECT_DOUBLE_EQ(plain.stack_v, 15.091787);
  EXPECT_DOUBLE_EQ(plain.min_v, 15.091787);
  EXPECT_DOUBLE_EQ(plain.max_v, 15.091787);
  EXPECT_DOUBLE_EQ(plain.temperature_c, 0.0);
  EXPECT_NEAR(plain.time_s, hms(15, 2, 18.154), 1e-9);

  const Cprbs with_id = parse_as<Cprbs>(sentence("CPRBS,150218.154,2,15.2,14.9,15.4,31.5"));
  EXPECT_EQ(with_id.battery_id, 2);
  EXPECT_DOUBLE_EQ(with_id.stack_v, 15.2);
  EXPECT_DOUBLE_EQ(with_id.min_v, 14.9);
  EXPECT_DOUBLE_EQ(with_id.max_v, 15.4);
  EXPECT_DOUBLE_EQ(with_id.temperature_c, 31.5);

  expect_error(sentence("CPRBS,150218.154,15.2,14.9,15.4"), Code::bad_field_count, 0, "5 or 6");
  expect_error(sentence("CPRBS,150218.154,1,2,15.2,14.9,15.4,0"), Code::bad_field_count, 0);
  expect_error(sentence("CPRBS,150218.154,2.5,15.2,14.9,15.4,31.5"), Code::non_numeric, 2,
               "battery id");
  expect_error(sentence("CPRBS,150218.154,-1,15.2,14.9,15.4,31.5"), Code::out_of_range, 2);
  expect_error(sentence("CPRBS,150218.154,-15.2,14.9,15.4,31.5"), Code::out_of_range, 2,
               "stack voltage");
  expect_error(sentence("CPRBS,150218.154,2,15.2,14.9,15.4,250"), Code::out_of_range, 6,
               "temperature");
}

TEST(NmeaCprcm, ParsesAndChecks) {
  const Cprcm s = parse_as<Cprcm>(kRealCprcm);
  EXPECT_EQ(s.compass_id, 0);
  EXPECT_DOUBLE_EQ(s.heading_deg, 234.326694);
  EXPECT_DOUBLE_EQ(s.pitch_deg, -1.655603);
  EXPECT_DOUBLE_EQ(s.roll_deg, -6.628557);
  EXPECT_NEAR(s.imu_time_s, hms(16, 49, 59.060), 1e-9);
  EXPECT_DOUBLE_EQ(parse_as<Cprcm>(sentence("CPRCM,000001,1,0,0,0,")).imu_time_s, 1.0);
  expect_error(sentence("CPRCM,164959.065,0,400,0,0,164959.060"), Code::out_of_range, 3, "heading");
  expect_error(sentence("CPRCM,164959.065,x,1,0,0,164959.060"), Code::non_numeric, 2, "compass id");
  expect_error(sentence("CPRCM,164959.065,0,1,0,0"), Code::bad_field_count, 0);
}

TEST(NmeaCpimu, ParsesAndChecks) {
  const Cpimu s = parse_as<Cpimu>(kRealCpimu);
  EXPECT_DOUBLE_EQ(s.rate_x_dps, -0.061035);
  EXPECT_DOUBLE_EQ(s.rate_y_dps, -0.000097);
  EXPECT_DOUBLE_EQ(s.rate_z_dps, -0.061035);
  EXPECT_DOUBLE_EQ(s.accel_x, -0.026916);
  EXPECT_DOUBLE_EQ(s.accel_y, 0.104533);
  EXPECT_DOUBLE_EQ(s.accel_z, -0.932172);
  expect_error(sentence("CPIMU,164958.858,0,0,0,0,0,1e3"), Code::non_numeric, 7, "acceleration z");
  expect_error(sentence("CPIMU,164958.858,0,0,0,0,0,1000.5"), Code::out_of_range, 7);
  expect_error(sentence("CPIMU,164958.858,0,0,0,0,0"), Code::bad_field_count, 0);
}

TEST(NmeaCpalt, ParsesAndChecks) {
  const Cpalt s = parse_as<Cpalt>(sentence("CPALT,101010,1"));
  EXPECT_DOUBLE_EQ(s.time_s, hms(10, 10, 10));
  EXPECT_DOUBLE_EQ(s.value, 1.0);
  EXPECT_DOUBLE_EQ(parse_as<Cpalt>(sentence("CPALT,101010,12.75")).value, 12.75);
  expect_error(sentence("CPALT,101010"), Code::bad_field_count, 0);
  expect_error(sentence("CPALT,101010,"), Code::missing_field, 2);
  expect_error(sentence("CPALT,101010,on"), Code::non_numeric, 2);
}

// ---- GPS sentences --------------------------------------------------------------------------

TEST(NmeaGprmc, ParsesTheRealSentence) {
  const Gprmc s = parse_as<Gprmc>(kRealGprmc);
  EXPECT_EQ(s.talker, "GP");
  EXPECT_NEAR(*s.time_s, hms(16, 49, 59), 1e-9);
  EXPECT_TRUE(s.valid);
  EXPECT_NEAR(*s.lat_deg, 42.0 + 21.71114 / 60.0, 1e-12);
  EXPECT_NEAR(*s.lon_deg, -(71.0 + 5.44878 / 60.0), 1e-12);  // zero-padded longitude
  EXPECT_DOUBLE_EQ(*s.speed_knots, 0.145);
  EXPECT_NEAR(*s.speed_mps(), 0.145 * 1852.0 / 3600.0, 1e-12);
  EXPECT_DOUBLE_EQ(*s.course_deg, 156.78);
  EXPECT_EQ(s.date, (NmeaDate{2014, 12, 31}));
  EXPECT_FALSE(s.magnetic_variation_deg);
  EXPECT_EQ(s.mode, 'A');
  EXPECT_FALSE(s.nav_status);
}

TEST(NmeaGprmc, NoFixAndOlderAndNewerLayouts) {
  // A receiver without a fix blanks nearly everything.
  const Gprmc none = parse_as<Gprmc>("$GPRMC,,V,,,,,,,,,,N*53");
  EXPECT_FALSE(none.valid);
  EXPECT_FALSE(none.time_s);
  EXPECT_FALSE(none.lat_deg);
  EXPECT_FALSE(none.lon_deg);
  EXPECT_FALSE(none.speed_knots);
  EXPECT_FALSE(none.speed_mps());
  EXPECT_FALSE(none.date);
  EXPECT_EQ(none.mode, 'N');
  // NMEA 2.2: 11 fields, no mode; a magnetic variation west.
  const Gprmc old =
      parse_as<Gprmc>(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W"));
  EXPECT_FALSE(old.mode);
  EXPECT_DOUBLE_EQ(*old.magnetic_variation_deg, -3.1);
  EXPECT_EQ(old.date, (NmeaDate{1994, 3, 23}));
  EXPECT_NEAR(*old.lon_deg, 11.0 + 31.0 / 60.0, 1e-12);
  // NMEA 4.1: 13 fields with the navigational status.
  const Gprmc v41 =
      parse_as<Gprmc>(sentence("GNRMC,001031.00,A,4404.13993,N,12118.86023,W,0.146,,100117,,,A,V"));
  EXPECT_EQ(v41.talker, "GN");
  EXPECT_EQ(v41.nav_status, 'V');
  EXPECT_FALSE(v41.course_deg);
}

TEST(NmeaGprmc, MalformedVariants) {
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1"),
               Code::bad_field_count, 0, "11 or 12 or 13");
  expect_error(sentence("GPRMC,123519,X,4807.038,N,01131.000,E,022.4,084.4,230394,,,A"),
               Code::bad_value, 2, "status");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,,E,022.4,084.4,230394,,,A"), Code::missing_field,
               5, "longitude");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,-1,084.4,230394,,,A"),
               Code::out_of_range, 7, "speed over ground");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,9999,084.4,230394,,,A"),
               Code::out_of_range, 7, "speed over ground");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,1,084.4,300294,,,A"),
               Code::out_of_range, 9, "date");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,1,084.4,2303944,,,A"),
               Code::bad_value, 9);
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,1,084.4,230394,3.1,,A"),
               Code::missing_field, 11, "magnetic variation direction");
  expect_error(sentence("GPRMC,123519,A,4807.038,N,01131.000,E,1,084.4,230394,,,Q"),
               Code::bad_value, 12, "mode");
  EXPECT_EQ(parse_as<Gprmc>(sentence("GPRMC,000000,A,,,,,,,290200,,,")).date,
            (NmeaDate{2000, 2, 29}));
}

TEST(NmeaGpgga, ParsesTheRealSentences) {
  const Gpgga s = parse_as<Gpgga>(kRealGpgga);
  EXPECT_EQ(s.talker, "GP");
  EXPECT_NEAR(*s.lat_deg, 42.0 + 21.71114 / 60.0, 1e-12);
  EXPECT_NEAR(*s.lon_deg, -(71.0 + 5.44878 / 60.0), 1e-12);
  EXPECT_EQ(s.quality, 1);
  EXPECT_EQ(s.satellites, 6);
  EXPECT_DOUBLE_EQ(*s.hdop, 2.8);
  EXPECT_DOUBLE_EQ(*s.altitude_m, 46.6);
  EXPECT_DOUBLE_EQ(*s.geoid_separation_m, -33.2);
  EXPECT_FALSE(s.dgps_age_s);
  EXPECT_FALSE(s.dgps_station);
  const Gpgga dgps = parse_as<Gpgga>(
      "$GPGGA,150216.20,4221.51616,N,07105.25215,W,2,10,0.84,19.5,M,-33.2,M,,0000*53");
  EXPECT_EQ(dgps.quality, 2);
  EXPECT_EQ(dgps.dgps_station, 0);
  const Gpgga none = parse_as<Gpgga>(sentence("GPGGA,,,,,,0,00,99.99,,,,,,"));
  EXPECT_FALSE(none.lat_deg);
  EXPECT_EQ(none.quality, 0);
  expect_error(sentence("GPGGA,,,,,,9,00,99.99,,,,,,"), Code::out_of_range, 6, "fix quality");
  expect_error(sentence("GPGGA,,,,,,,00,99.99,,,,,,"), Code::missing_field, 6);
  expect_error(sentence("GPGGA,,,,,,1,00,99.99,46.6,F,,,,"), Code::bad_value, 10, "altitude unit");
  expect_error(sentence("GPGGA,,,,,,1,00,99.99,,,,,,,"), Code::bad_field_count, 0);
  expect_error(sentence("GPGGA,,,,,,1,00,99.99,,,,,,2000"), Code::out_of_range, 14);
}

TEST(NmeaGpvtg, ParsesAndChecks) {
  const Gpvtg s = parse_as<Gpvtg>(kRealGpvtg);
  EXPECT_DOUBLE_EQ(*s.course_true_deg, 156.78);
  EXPECT_FALSE(s.course_magnetic_deg);
  EXPECT_DOUBLE_EQ(*s.speed_knots, 0.145);
  EXPECT_DOUBLE_EQ(*s.speed_kmh, 0.269);
  EXPECT_NEAR(*s.speed_mps(), 0.145 * 1852.0 / 3600.0, 1e-12);
  EXPECT_EQ(s.mode, 'A');
  const Gpvtg old = parse_as<Gpvtg>(sentence("GPVTG,054.7,T,034.4,M,005.5,N,010.2,K"));
  EXPECT_FALSE(old.mode);
  EXPECT_DOUBLE_EQ(*old.course_magnetic_deg, 34.4);
  expect_error(sentence("GPVTG,054.7,T,034.4,M,005.5,N,010.2,X"), Code::bad_value, 8);
  expect_error(sentence("GPVTG,054.7,034.4,005.5,010.2"), Code::bad_field_count, 0);
  // Speeds are bounded as a navigation sample's (100 m/s) in the sentence's own units, so that
  // what the station stores reads back from its recordings.
  expect_error(sentence("GPVTG,054.7,T,034.4,M,194.5,N,010.2,K"), Code::out_of_range, 5,
               "speed knots");
  expect_error(sentence("GPVTG,054.7,T,034.4,M,005.5,N,360.1,K"), Code::out_of_range, 7,
               "speed km/h");
  EXPECT_DOUBLE_EQ(*parse_as<Gpvtg>(sentence("GPVTG,054.7,T,034.4,M,194.3,N,359.9,K")).speed_kmh,
                   359.9);
}

TEST(NmeaGps, GnssTalkersMapToTheSameTypes) {
  const Gprmc rmc = parse_as<Gprmc>(
      sentence("GNRMC,164959.00,A,4221.71114,N,07105.44878,W,0.145,156.78,311214,,,A"));
  EXPECT_EQ(rmc.talker, "GN");
  Gprmc gp = parse_as<Gprmc>(kRealGprmc);
  gp.talker = "GN";
  EXPECT_EQ(rmc, gp);
  EXPECT_EQ(parse_as<Gpgga>(sentence("GNGGA,,,,,,0,,,,,,,,")).talker, "GN");
  EXPECT_EQ(parse_as<Gpvtg>(sentence("GLVTG,,T,,M,,N,,K,N")).talker, "GL");
  // Not a GNSS talker: a well-formed sentence of an unknown kind.
  const auto other = parse_as<UnknownSentence>(sentence("IIRMC,1,2"));
  EXPECT_EQ(other.address, "IIRMC");
}

TEST(NmeaUnknown, KeepsAddressAndFields) {
  const auto s = parse_as<UnknownSentence>(kRealGpgsa);
  EXPECT_EQ(s.address, "GPGSA");
  ASSERT_EQ(s.fields.size(), 17u);
  EXPECT_EQ(s.fields[0], "A");
  EXPECT_EQ(s.fields[3], "02");
  EXPECT_EQ(s.fields[16], "3.46");
  const auto bare = parse_as<UnknownSentence>(sentence("CPTIME"));
  EXPECT_TRUE(bare.fields.empty());
  EXPECT_EQ(parse_as<UnknownSentence>(sentence("CPTIME,")).fields, std::vector<std::string>{""});
}

// ---- Backseat sentences ---------------------------------------------------------------------

TEST(NmeaPydir, ParsesAndChecks) {
  EXPECT_EQ(parse_as<Pydir>(sentence("PYDIR,-100,100"), kToFrontseat), (Pydir{-100.0, 100.0}));
  EXPECT_EQ(parse_as<Pydir>("$PYDIR,0.5,-0.25*", kToFrontseat), (Pydir{0.5, -0.25}));
  expect_error(sentence("PYDIR,100.01,0"), Code::out_of_range, 1, "left thrust", kToFrontseat);
  expect_error(sentence("PYDIR,0,-101"), Code::out_of_range, 2, "right thrust", kToFrontseat);
  expect_error(sentence("PYDIR,0,"), Code::missing_field, 2, "right thrust", kToFrontseat);
  expect_error(sentence("PYDIR,0,1,2"), Code::bad_field_count, 0, "3 fields", kToFrontseat);
  expect_error(sentence("PYDIR"), Code::bad_field_count, 0, "0 fields", kToFrontseat);
  expect_error("$PYDIR,50%,50%", Code::non_numeric, 1, "left thrust", kToFrontseat);
  expect_error("$PYDIR,nan,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR,inf,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR,0x10,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR,1.2.3,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR,--5,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR, 5,0", Code::non_numeric, 1, "", kToFrontseat);
  expect_error("$PYDIR,.,0", Code::non_numeric, 1, "", kToFrontseat);
}

TEST(NmeaPydev, ParsesAndChecks) {
  EXPECT_EQ(parse_as<Pydev>(sentence("PYDEV,270.5,1.5"), kToFrontseat), (Pydev{270.5, 1.5}));
  expect_error(sentence("PYDEV,360.1,1.5"), Code::out_of_range, 1, "heading", kToFrontseat);
  expect_error(sentence("PYDEV,90,-0.5"), Code::out_of_range, 2, "speed", kToFrontseat);
  expect_error(sentence("PYDEV,90"), Code::bad_field_count, 0, "", kToFrontseat);
}

TEST(NmeaPydep, ParsesAndChecks) {
  EXPECT_EQ(parse_as<Pydep>(sentence("PYDEP,-12.5,60"), kToFrontseat), (Pydep{-12.5, 60.0}));
  expect_error(sentence("PYDEP,-12.5,160"), Code::out_of_range, 2, "thrust", kToFrontseat);
  expect_error(sentence("PYDEP,fast,60"), Code::non_numeric, 1, "yaw rate", kToFrontseat);
}

TEST(NmeaPyclt, ParsesAndChecks) {
  EXPECT_TRUE(parse_as<Pyclt>(sentence("PYCLT,1"), kToFrontseat).lights_on);
  EXPECT_FALSE(parse_as<Pyclt>("$PYCLT,0", kToFrontseat).lights_on);
  expect_error(sentence("PYCLT,2"), Code::bad_value, 1, "lights", kToFrontseat);
  expect_error(sentence("PYCLT,1,0"), Code::bad_field_count, 0, "", kToFrontseat);
}

}  // namespace
