// The frontseat protocol parser and formatters: real M200 output, every sentence type, the
// malformed variants (checksum, framing, field count, numbers, ranges), the checksum rules of the
// two directions, formatter round trips, and random mutations that must never crash the parser.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "support/nmea_sentence.hpp"
#include "vehicle/nmea.hpp"

namespace {

using namespace avk::vehicle;
using Code = NmeaError::Code;

constexpr auto kFromFrontseat = NmeaDirection::frontseat_to_backseat;
constexpr auto kToFrontseat = NmeaDirection::backseat_to_frontseat;

std::string sentence(std::string_view body) {
  return avk::testing::nmea_sentence(body);
}

double hms(int h, int m, double s) {
  return h * 3600.0 + m * 60.0 + s;
}

template <class T>
T parse_as(std::string_view line, NmeaDirection direction = kFromFrontseat) {
  const NmeaParseResult r = parse_sentence(line, direction);
  if (const NmeaError* e = r.error()) {
    ADD_FAILURE() << "'" << line << "': " << e->message;
    return T{};
  }
  if (!std::holds_alternative<T>(*r.sentence())) {
    ADD_FAILURE() << "'" << line << "' parsed as alternative " << r.sentence()->index();
    return T{};
  }
  return std::get<T>(*r.sentence());
}

NmeaSentence parse_any(std::string_view line) {
  const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
  if (const NmeaError* e = r.error()) {
    ADD_FAILURE() << "'" << line << "': " << e->message;
    return NmeaSentence{};
  }
  return *r.sentence();
}

NmeaError parse_error(std::string_view line, NmeaDirection direction = kFromFrontseat) {
  const NmeaParseResult r = parse_sentence(line, direction);
  if (!r.error()) {
    ADD_FAILURE() << "'" << line << "' parsed";
    return NmeaError{};
  }
  return *r.error();
}

void expect_error(std::string_view line, Code code, std::size_t field,
                  std::string_view mentions = {}, NmeaDirection direction = kFromFrontseat) {
  const NmeaError e = parse_error(line, direction);
  EXPECT_EQ(to_string(e.code), std::string(to_string(code))) << line << ": " << e.message;
  EXPECT_EQ(e.field, field) << line << ": " << e.message;
  EXPECT_FALSE(e.message.empty());
  if (!mentions.empty()) {
    EXPECT_NE(e.message.find(mentions), std::string::npos) << e.message << " / " << mentions;
  }
}

// Recorded from a Kingfisher M200 on the Charles (published with the MOOS-IvP M200 emulator):
// the checksums are the frontseat's own.
const char* const kRealCpimu =
    "$CPIMU,164958.858,-0.061035,-0.000097,-0.061035,-0.026916,0.104533,-0.932172*57";
const char* const kRealGprmc =
    "$GPRMC,164959.00,A,4221.71114,N,07105.44878,W,0.145,156.78,311214,,,A*70";
const char* const kRealGpvtg = "$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3D";
const char* const kRealGpgga =
    "$GPGGA,164959.00,4221.71114,N,07105.44878,W,1,06,2.80,46.6,M,-33.2,M,,*5C";
const char* const kRealGpgsa = "$GPGSA,A,3,29,02,26,05,13,15,,,,,,,4.45,2.80,3.46*02";
const char* const kRealCpnvg =
    "$CPNVG,164959.034,4221.711142,N,7105.44878,W,1,0,0,234.32964,-6.796959,-1.706798,164959."
    "006*78";
const char* const kRealCpnvr = "$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*59";
const char* const kRealCprcm = "$CPRCM,164959.065,0,234.326694,-1.655603,-6.628557,164959.060*62";
const char* const kRealCprbs = "$CPRBS,150218.154,15.091787,15.091787,15.091787,0*77";

const char* const kRealLines[] = {kRealCpimu, kRealGprmc, kRealGpvtg, kRealGpgga, kRealGpgsa,
                                  kRealCpnvg, kRealCpnvr, kRealCprcm, kRealCprbs};

// ---- Checksums and framing ------------------------------------------------------------------

TEST(NmeaChecksum, XorsTheBytesBetweenDollarAndStar) {
  EXPECT_EQ(nmea_checksum(""), 0);
  EXPECT_EQ(nmea_checksum("A"), 0x41);
  EXPECT_EQ(nmea_checksum("AA"), 0);
  EXPECT_EQ(nmea_checksum("GPGSA,A,3,29,02,26,05,13,15,,,,,,,4.45,2.80,3.46"), 0x02);
  EXPECT_EQ(nmea_checksum("PYDIR,0,0"), 0x56);
  EXPECT_EQ(nmea_checksum("PYDIR,0,0"), nmea_checksum("PYDIR"));  // ",0" twice cancels out
  for (const char* line : kRealLines) {
    const std::string_view s(line);
    const std::size_t star = s.find('*');
    EXPECT_EQ(nmea_checksum(s.substr(1, star - 1)),
              std::stoi(std::string(s.substr(star + 1)), nullptr, 16))
        << line;
  }
}

TEST(NmeaParse, RealFrontseatOutputParses) {
  for (const char* line : kRealLines) {
    const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
    ASSERT_TRUE(r.ok()) << line << ": " << r.error()->message;
    EXPECT_EQ(r.checksum, NmeaChecksum::upper_case);
  }
}

TEST(NmeaParse, StripsTrailingLineEndings) {
  for (const char* ending : {"", "\r\n", "\n", "\r", "\r\n\r\n", "\n\r"}) {
    const std::string line = std::string(kRealCpnvr) + ending;
    const Cpnvr s = parse_as<Cpnvr>(line);
    EXPECT_DOUBLE_EQ(s.yaw_rate_dps, -0.061132) << "ending of " << std::string_view(ending).size();
  }
  // A line ending inside the sentence is not a line ending.
  expect_error("$PYDIR,1\r\n,2*00", Code::bad_character, 0, "0x0D");
}

TEST(NmeaParse, EmptyLines) {
  for (const char* line : {"", "\r\n", "\n", "\r\r\n"})
    expect_error(line, Code::empty, 0);
}

TEST(NmeaParse, MissingDollar) {
  expect_error("GPRMC,,V,,,,,,,,,,N*53", Code::no_dollar, 0);
  expect_error(" $PYDIR,0,0*56", Code::no_dollar, 0);
  expect_error("!AIVDM,1,1,,A,13aEOK?P00PD2wVMdLDRhgvL289?,0*26", Code::no_dollar, 0);
  expect_error("*", Code::no_dollar, 0);
}

TEST(NmeaParse, OversizedLines) {
  // An unknown sentence padded to exactly the limit parses; one byte more does not. The line
  // ending does not count.
  const std::string head = "CPXXX,";
  std::string body = head + std::string(kNmeaMaxLineBytes - 4 - head.size(), '7');
  const std::string at_limit = sentence(body);
  ASSERT_EQ(at_limit.size(), kNmeaMaxLineBytes + 2);
  EXPECT_TRUE(parse_sentence(at_limit, kFromFrontseat).ok());
  expect_error(sentence(body + "7"), Code::oversized, 0, "257");
  // Without a checksum, a backseat line counts the three bytes the checksum would take.
  EXPECT_TRUE(parse_sentence("$" + body, kToFrontseat).ok());
  expect_error("$" + body + "7", Code::oversized, 0, "257", kToFrontseat);
  expect_error("$" + body + "7*", Code::oversized, 0, "257", kToFrontseat);
  expect_error("$" + std::string(1 << 20, 'A'), Code::oversized, 0);
  expect_error(std::string(1000, '\0'), Code::oversized, 0);
}

TEST(NmeaParse, BadCharacters) {
  std::string with_nul = "$PYDIR,1,2*00";
  with_nul[8] = '\0';
  expect_error(with_nul, Code::bad_character, 0, "0x00");
  expect_error("$PYDIR,1,\xff*00", Code::bad_character, 0, "0xFF");
  expect_error("$PYDIR,1,\t2*00", Code::bad_character, 0, "0x09");
  // Two sentences run together (a lost line ending).
  expect_error("$PYDIR,1,2$PYDIR,1,2*00", Code::bad_character, 0, "0x24");
}

TEST(NmeaParse, BadAddress) {
  expect_error(sentence("gprmc,,V,,,,,,,,,,N"), Code::bad_address, 0, "gprmc");
  expect_error(sentence(",1,2"), Code::bad_address, 0);
  expect_error(sentence("P,1,2"), Code::bad_address, 0);
  expect_error(sentence("PYDIR ,1,2"), Code::bad_address, 0);
  expect_error(sentence("ABCDEFGHIJK,1"), Code::bad_address, 0);
  expect_error(sentence(""), Code::bad_address, 0);
}

// ---- Checksum rules per direction -----------------------------------------------------------

TEST(NmeaParse, FrontseatSentencesNeedAChecksum) {
  expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132", Code::missing_checksum,
               0);
  expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*",
               Code::missing_checksum, 0);
  expect_error("$PYDIR,0,0\r\n", Code::missing_checksum, 0);
}

TEST(NmeaParse, ChecksumMustMatchInBothDirections) {
  for (NmeaDirection d : {kFromFrontseat, kToFrontseat}) {
    expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*58",
                 Code::bad_checksum, 0, "59", d);
    expect_error("$PYDIR,0,0*57", Code::bad_checksum, 0, "56", d);
    expect_error("$PYDIR,0,0*5", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*560", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*G6", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0* 56", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*56*56", Code::bad_checksum, 0, "two hex digits", d);
  }
}

TEST(NmeaParse, LowerCaseChecksumIsAcceptedAndNoted) {
  const NmeaParseResult r =
      parse_sentence("$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3d\r\n", kFromFrontseat);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.checksum, NmeaChecksum::lower_case);
  const NmeaParseResult upper = parse_sentence(kRealGpvtg, kFromFrontseat);
  EXPECT_EQ(upper.checksum, NmeaChecksum::upper_case);
  EXPECT_EQ(*r.sentence(), *upper.sentence());
  expect_error("$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3e", Code::bad_checksum, 0);
}

TEST(NmeaParse, BackseatSentencesMayOmitTheChecksum) {
  // As older drivers sent them: no digits after `*`, or no `*` at all.
  const NmeaParseResult blank = parse_sentence("$PYDIR,25.5,-40*\r\n", kToFrontseat);
  ASSERT_TRUE(blank.ok());
  EXPECT_EQ(blank.checksum, NmeaChecksum::blank);
  EXPECT_EQ(std::get<Pydir>(*blank.sentence()), (Pydir{25.5, -40.0}));
  const NmeaParseResult absent = parse_sentence("$PYDIR,25.5,-40", kToFrontseat);
  ASSERT_TRUE(absent.ok());
  EXPECT_EQ(absent.checksum, NmeaChecksum::absent);
  const NmeaParseResult present = parse_sentence(sentence("PYDIR,25.5,-40"), kToFrontseat);
  ASSERT_TRUE(present.ok());
  EXPECT_EQ(present.checksum, NmeaChecksum::upper_case);
  // The frontseat holds its own sentences to the stricter rule.
  expect_error("$PYDIR,25.5,-40*", Code::missing_checksum, 0);
}

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

// ---- Hostile input --------------------------------------------------------------------------

// Random mutations of valid sentences: byte flips, insertions, deletions, truncations, swaps,
// spliced delimiters and field garbage, half of them with the checksum fixed afterwards so the
// field parsers see them too. Nothing may throw or crash, and every result is a sentence or an
// error; an accepted sentence writes and reads back as the same type.
TEST(NmeaParse, RandomMutationsNeverCrash) {
  std::vector<std::string> seeds(std::begin(kRealLines), std::end(kRealLines));
  for (const char* body :
       {"PYDIR,-12.5,40", "PYDEV,270,1.5", "PYDEP,-3,50", "PYCLT,1", "CPALT,101010,1",
        "CPRBS,150218.154,2,15.2,14.9,15.4,31.5", "GNRMC,,V,,,,,,,,,,N",
        "GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W",
        "GNRMC,001031.00,A,4404.13993,N,12118.86023,W,0.146,,100117,,,A,V",
        "GPGGA,,,,,,0,00,99.99,,,,,,", "GPVTG,054.7,T,034.4,M,005.5,N,010.2,K"})
    seeds.push_back(sentence(body));
  const std::string specials = ",*$.-+0123456789ENSWAV\r\n";

  std::mt19937_64 rng(8);
  auto below = [&](std::size_t n) {
    return n == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  std::size_t parsed = 0, failed = 0, thrown = 0;
  std::size_t codes[16] = {};
  for (int i = 0; i < 100000; ++i) {
    std::string s = seeds[below(seeds.size())];
    const std::size_t mutations = 1 + below(4);
    for (std::size_t m = 0; m < mutations; ++m) {
      const std::size_t at = below(s.size() + 1);
      const char byte = static_cast<char>(below(256));
      const char special = specials[below(specials.size())];
      switch (below(8)) {
        case 0:
          if (at < s.size()) s[at] = byte;
          break;
        case 1:
          s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), special);
          break;
        case 2:
          if (at < s.size()) s.erase(at, 1 + below(4));
          break;
        case 3:
          s.resize(at);
          break;
        case 4:
          if (at < s.size()) std::swap(s[at], s[below(s.size())]);
          break;
        case 5:
          if (at < s.size()) s[at] = special;
          break;
        case 6:  // a field's digits into something else
          s.insert(at, std::string(1 + below(12), "9.-e"[below(4)]));
          break;
        case 7:
          s.insert(at, s.substr(below(s.size()), below(40)));
          break;
      }
    }
    if (below(2) == 0) {
      // Fix the checksum so the mutation reaches the field parsers.
      const std::size_t star = s.find('*');
      if (!s.empty() && s[0] == '$' && star != std::string::npos) {
        char sum[4];
        std::snprintf(
            sum, sizeof sum, "%02X",
            static_cast<unsigned>(nmea_checksum(std::string_view(s).substr(1, star - 1))));
        s.replace(star + 1, std::min<std::size_t>(2, s.size() - star - 1), sum);
      }
    }
    for (NmeaDirection d : {kFromFrontseat, kToFrontseat}) {
      try {
        const NmeaParseResult r = parse_sentence(s, d);
        ASSERT_FALSE(r.value.valueless_by_exception());
        if (const NmeaError* e = r.error()) {
          ++failed;
          ++codes[static_cast<int>(e->code)];
          ASSERT_FALSE(e->message.empty());
          ASSERT_LE(e->field, 16u) << e->message;
        } else {
          ++parsed;
          ASSERT_FALSE(r.sentence()->valueless_by_exception());
          const std::string again = format_sentence(*r.sentence());
          const NmeaParseResult back = parse_sentence(again, kFromFrontseat);
          ASSERT_TRUE(back.ok()) << s << " -> " << again;
          ASSERT_EQ(back.sentence()->index(), r.sentence()->index()) << s << " -> " << again;
          ASSERT_EQ(format_sentence(*back.sentence()), again) << s;
        }
      } catch (const std::exception& e) {
        ++thrown;
        ADD_FAILURE() << "threw on '" << s << "': " << e.what();
      }
    }
  }
  RecordProperty("parsed", static_cast<int>(parsed));
  RecordProperty("failed", static_cast<int>(failed));
  EXPECT_EQ(thrown, 0u);
  EXPECT_EQ(parsed + failed, 200000u);
  // Both outcomes are common, and the field-level errors are reached, not only the framing.
  EXPECT_GT(parsed, 10000u);
  EXPECT_GT(failed, 50000u);
  for (Code c : {Code::bad_checksum, Code::bad_field_count, Code::non_numeric, Code::out_of_range,
                 Code::missing_field, Code::bad_value, Code::bad_character})
    EXPECT_GT(codes[static_cast<int>(c)], 100u) << to_string(c);
}

TEST(NmeaError, CodesHaveNames) {
  EXPECT_STREQ(to_string(Code::bad_checksum), "bad_checksum");
  EXPECT_STREQ(to_string(Code::out_of_range), "out_of_range");
  EXPECT_STREQ(to_string(Code::empty), "empty");
}

}  // namespace
