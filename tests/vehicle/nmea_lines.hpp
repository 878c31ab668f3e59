#pragma once
// Frontseat protocol lines for the parser's tests: sentences with their checksum, parses that must
// succeed or fail as the test says, and lines recorded from a real M200.

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

namespace avk::testing::nmea_lines {

using namespace avk::vehicle;
using Code = NmeaError::Code;

inline constexpr auto kFromFrontseat = NmeaDirection::frontseat_to_backseat;
inline constexpr auto kToFrontseat = NmeaDirection::backseat_to_frontseat;

inline std::string sentence(std::string_view body) {
  return avk::testing::nmea_sentence(body);
}

inline double hms(int h, int m, double s) {
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

inline NmeaSentence parse_any(std::string_view line) {
  const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
  if (const NmeaError* e = r.error()) {
    ADD_FAILURE() << "'" << line << "': " << e->message;
    return NmeaSentence{};
  }
  return *r.sentence();
}

inline NmeaError parse_error(std::string_view line, NmeaDirection direction = kFromFrontseat) {
  const NmeaParseResult r = parse_sentence(line, direction);
  if (!r.error()) {
    ADD_FAILURE() << "'" << line << "' parsed";
    return NmeaError{};
  }
  return *r.error();
}

inline void expect_error(std::string_view line, Code code, std::size_t field,
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
inline const char* const kRealCpimu =
    "$CPIMU,164958.858,-0.061035,-0.000097,-0.061035,-0.026916,0.104533,-0.932172*57";
inline const char* const kRealGprmc =
    "$GPRMC,164959.00,A,4221.71114,N,07105.44878,W,0.145,156.78,311214,,,A*70";
inline const char* const kRealGpvtg = "$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3D";
inline const char* const kRealGpgga =
    "$GPGGA,164959.00,4221.71114,N,07105.44878,W,1,06,2.80,46.6,M,-33.2,M,,*5C";
inline const char* const kRealGpgsa = "$GPGSA,A,3,29,02,26,05,13,15,,,,,,,4.45,2.80,3.46*02";
inline const char* const kRealCpnvg =
    "$CPNVG,164959.034,4221.711142,N,7105.44878,W,1,0,0,234.32964,-6.796959,-1.706798,164959."
    "006*78";
inline const char* const kRealCpnvr =
    "$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*59";
inline const char* const kRealCprcm =
    "$CPRCM,164959.065,0,234.326694,-1.655603,-6.628557,164959.060*62";
inline const char* const kRealCprbs = "$CPRBS,150218.154,15.091787,15.091787,15.091787,0*77";

inline const char* const kRealLines[] = {kRealCpimu, kRealGprmc, kRealGpvtg, kRealGpgga, kRealGpgsa,
                                         kRealCpnvg, kRealCpnvr, kRealCprcm, kRealCprbs};

}  // namespace avk::testing::nmea_lines
