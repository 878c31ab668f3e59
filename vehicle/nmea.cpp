#include "vehicle/nmea.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "vehicle/nav_ranges.hpp"
#include "vehicle/nmea_fields.hpp"
#include "vehicle/nmea_text.hpp"

namespace avk::vehicle {

namespace {

using namespace nmea;

// Navigation ranges are the ones every reader of navigation shares (vehicle/nav_ranges.hpp).
// Beyond the protocol's own limits (thrust, latitudes), the bounds of the others are far outside
// anything a small boat reports: they catch garbage that passed the checksum (a firmware bug, a
// corrupted but consistent relay), not unusual motion.
constexpr Range kThrust{-100.0, 100.0};
constexpr Range kAcceleration{-1000.0, 1000.0};
constexpr Range kRoll{-180.0, 180.0};
constexpr Range kPitch{-90.0, 90.0};
constexpr Range kDepth{-100.0, 12000.0};  // a pressure sensor may read a little above the surface
constexpr Range kVoltage{0.0, 1000.0};
constexpr Range kTemperature{-100.0, 200.0};
constexpr Range kCpaltValue{-1e5, 1e5};
// The speeds a navigation sample may carry (kSpeedRange_mps) in the sentence's own unit: a
// speed the station would store must read back from its own recordings.
constexpr Range kSpeedKnots{0.0, kSpeedRange_mps.high / kMetresPerSecondPerKnot};
constexpr Range kSpeedKmh{0.0, kSpeedRange_mps.high * 3.6};
constexpr Range kMagneticVariation{0.0, 180.0};
constexpr Range kHdop{0.0, 100.0};
constexpr Range kGpsAltitude{-10000.0, 100000.0};
constexpr Range kGeoidSeparation{-1000.0, 1000.0};
constexpr Range kDgpsAge{0.0, 100000.0};

template <class T>
std::variant<NmeaSentence, NmeaError> finish(Reader& r, T&& sentence) {
  if (r.failed()) return r.take_error();
  return NmeaSentence(std::forward<T>(sentence));
}

std::variant<NmeaSentence, NmeaError> parse_cpnvg(Reader& r) {
  if (!r.expect_count({12})) return r.take_error();
  Cpnvg s;
  s.time_s = r.time(1, "time");
  std::optional<double> lat, lon;
  r.position(2, true, lat, lon);
  s.lat_deg = lat.value_or(0.0);
  s.lon_deg = lon.value_or(0.0);
  s.position_ok = r.flag(6, "position quality", "01") == '1';
  s.altitude_m = r.maybe_number(7, "altitude", kDepth);
  s.depth_m = r.maybe_number(8, "depth", kDepth);
  s.heading_deg = r.heading(9, "heading");
  s.roll_deg = r.number(10, "roll", kRoll);
  s.pitch_deg = r.number(11, "pitch", kPitch);
  s.nav_time_s = r.maybe_time(12, "nav timestamp").value_or(s.time_s);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_cpnvr(Reader& r) {
  if (!r.expect_count({7})) return r.take_error();
  Cpnvr s;
  s.time_s = r.time(1, "time");
  s.v_east_mps = r.number(2, "v east", kVelocityRange_mps);
  s.v_north_mps = r.number(3, "v north", kVelocityRange_mps);
  s.v_down_mps = r.number(4, "v down", kVelocityRange_mps);
  s.pitch_rate_dps = r.number(5, "pitch rate", kRateRange_dps);
  s.roll_rate_dps = r.number(6, "roll rate", kRateRange_dps);
  s.yaw_rate_dps = r.number(7, "yaw rate", kRateRange_dps);
  // Each component may be within its range while the speed they make is not: the horizontal
  // speed becomes the sample's speed, so it must be one.
  if (!r.failed() && !kSpeedRange_mps.contains(std::hypot(s.v_east_mps, s.v_north_mps)))
    r.fail(Code::out_of_range, 2, "v east",
           "horizontal speed " + std::to_string(std::hypot(s.v_east_mps, s.v_north_mps)) +
               " m/s is out of range " + to_string(kSpeedRange_mps));
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_cprbs(Reader& r) {
  if (!r.expect_count({5, 6})) return r.take_error();
  Cprbs s;
  s.time_s = r.time(1, "time");
  std::size_t i = 2;
  if (r.count() == 6) s.battery_id = r.integer(i++, "battery id", 0, 999);
  s.stack_v = r.number(i++, "stack voltage", kVoltage);
  s.min_v = r.number(i++, "min voltage", kVoltage);
  s.max_v = r.number(i++, "max voltage", kVoltage);
  s.temperature_c = r.number(i, "temperature", kTemperature);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_cprcm(Reader& r) {
  if (!r.expect_count({6})) return r.take_error();
  Cprcm s;
  s.time_s = r.time(1, "time");
  s.compass_id = r.integer(2, "compass id", 0, 999);
  s.heading_deg = r.heading(3, "heading");
  s.pitch_deg = r.number(4, "pitch", kPitch);
  s.roll_deg = r.number(5, "roll", kRoll);
  s.imu_time_s = r.maybe_time(6, "imu timestamp").value_or(s.time_s);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_cpimu(Reader& r) {
  if (!r.expect_count({7})) return r.take_error();
  Cpimu s;
  s.time_s = r.time(1, "time");
  s.rate_x_dps = r.number(2, "rate x", kRateRange_dps);
  s.rate_y_dps = r.number(3, "rate y", kRateRange_dps);
  s.rate_z_dps = r.number(4, "rate z", kRateRange_dps);
  s.accel_x = r.number(5, "acceleration x", kAcceleration);
  s.accel_y = r.number(6, "acceleration y", kAcceleration);
  s.accel_z = r.number(7, "acceleration z", kAcceleration);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_cpalt(Reader& r) {
  if (!r.expect_count({2})) return r.take_error();
  Cpalt s;
  s.time_s = r.time(1, "time");
  s.value = r.number(2, "value", kCpaltValue);
  return finish(r, std::move(s));
}

// NMEA 2.2 and earlier have 11 fields; 2.3 adds the mode, 4.1 the navigational status.
std::variant<NmeaSentence, NmeaError> parse_rmc(Reader& r, std::string_view talker) {
  if (!r.expect_count({11, 12, 13})) return r.take_error();
  Gprmc s;
  s.talker = std::string(talker);
  s.time_s = r.maybe_time(1, "time");
  s.valid = r.flag(2, "status", "AV") == 'A';
  r.position(3, false, s.lat_deg, s.lon_deg);
  s.speed_knots = r.maybe_number(7, "speed over ground", kSpeedKnots);
  s.course_deg = r.maybe_heading(8, "course over ground");
  s.date = r.maybe_date(9, "date");
  const auto variation = r.maybe_number(10, "magnetic variation", kMagneticVariation);
  const auto side = r.maybe_flag(11, "magnetic variation direction", "EW");
  if (variation && !side)
    r.fail(Code::missing_field, 11, "magnetic variation direction", "is blank");
  if (variation) s.magnetic_variation_deg = side == 'W' ? -*variation : *variation;
  if (r.count() >= 12) s.mode = r.maybe_flag(12, "mode", "ADEFMNPRS");
  if (r.count() >= 13) s.nav_status = r.maybe_flag(13, "navigational status", "SCUV");
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_gga(Reader& r, std::string_view talker) {
  if (!r.expect_count({14})) return r.take_error();
  Gpgga s;
  s.talker = std::string(talker);
  s.time_s = r.maybe_time(1, "time");
  r.position(2, false, s.lat_deg, s.lon_deg);
  s.quality = r.integer(6, "fix quality", 0, 8);
  s.satellites = r.maybe_integer(7, "satellites", 0, 99);
  s.hdop = r.maybe_number(8, "hdop", kHdop);
  s.altitude_m = r.maybe_number(9, "altitude", kGpsAltitude);
  r.unit(10, "altitude unit", 'M');
  s.geoid_separation_m = r.maybe_number(11, "geoid separation", kGeoidSeparation);
  r.unit(12, "geoid separation unit", 'M');
  s.dgps_age_s = r.maybe_number(13, "dgps age", kDgpsAge);
  s.dgps_station = r.maybe_integer(14, "dgps station", 0, 1023);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_vtg(Reader& r, std::string_view talker) {
  if (!r.expect_count({8, 9})) return r.take_error();
  Gpvtg s;
  s.talker = std::string(talker);
  s.course_true_deg = r.maybe_heading(1, "course true");
  r.unit(2, "course true unit", 'T');
  s.course_magnetic_deg = r.maybe_heading(3, "course magnetic");
  r.unit(4, "course magnetic unit", 'M');
  s.speed_knots = r.maybe_number(5, "speed knots", kSpeedKnots);
  r.unit(6, "speed knots unit", 'N');
  s.speed_kmh = r.maybe_number(7, "speed km/h", kSpeedKmh);
  r.unit(8, "speed km/h unit", 'K');
  if (r.count() == 9) s.mode = r.maybe_flag(9, "mode", "ADEFMNPRS");
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_pydir(Reader& r) {
  if (!r.expect_count({2})) return r.take_error();
  Pydir s;
  s.left_pct = r.number(1, "left thrust", kThrust);
  s.right_pct = r.number(2, "right thrust", kThrust);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_pydev(Reader& r) {
  if (!r.expect_count({2})) return r.take_error();
  Pydev s;
  s.heading_deg = r.heading(1, "heading");
  s.speed_mps = r.number(2, "speed", kSpeedRange_mps);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_pydep(Reader& r) {
  if (!r.expect_count({2})) return r.take_error();
  Pydep s;
  s.yaw_rate_dps = r.number(1, "yaw rate", kRateRange_dps);
  s.thrust_pct = r.number(2, "thrust", kThrust);
  return finish(r, std::move(s));
}

std::variant<NmeaSentence, NmeaError> parse_pyclt(Reader& r) {
  if (!r.expect_count({1})) return r.take_error();
  Pyclt s;
  s.lights_on = r.flag(1, "lights", "01") == '1';
  return finish(r, std::move(s));
}

UnknownSentence unknown(std::string_view address, std::string_view rest, bool has_fields) {
  UnknownSentence s;
  s.address = std::string(address);
  if (!has_fields) return s;
  for (;;) {
    const std::size_t comma = rest.find(',');
    s.fields.emplace_back(rest.substr(0, comma));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return s;
}

std::variant<NmeaSentence, NmeaError> parse_body(std::string_view body) {
  const std::size_t comma = body.find(',');
  const std::string_view address = body.substr(0, comma);
  const bool has_fields = comma != std::string_view::npos;
  const std::string_view rest = has_fields ? body.substr(comma + 1) : std::string_view();
  bool address_ok = address.size() >= 2 && address.size() <= 10;
  for (char c : address)
    address_ok = address_ok && ((c >= 'A' && c <= 'Z') || is_digit(c));
  if (!address_ok)
    return NmeaError{Code::bad_address,
                     "sentence id " + quoted(address) + " is not 2 to 10 letters A-Z and digits",
                     0};

  const Fields fields(rest, has_fields);
  Reader r(address, fields);
  if (address.size() == 5 && is_gnss_talker(address.substr(0, 2))) {
    const std::string_view type = address.substr(2);
    const std::string_view talker = address.substr(0, 2);
    if (type == "RMC") return parse_rmc(r, talker);
    if (type == "GGA") return parse_gga(r, talker);
    if (type == "VTG") return parse_vtg(r, talker);
  }
  if (address == "CPNVG") return parse_cpnvg(r);
  if (address == "CPNVR") return parse_cpnvr(r);
  if (address == "CPRBS") return parse_cprbs(r);
  if (address == "CPRCM") return parse_cprcm(r);
  if (address == "CPIMU") return parse_cpimu(r);
  if (address == "CPALT") return parse_cpalt(r);
  if (address == "PYDIR") return parse_pydir(r);
  if (address == "PYDEV") return parse_pydev(r);
  if (address == "PYDEP") return parse_pydep(r);
  if (address == "PYCLT") return parse_pyclt(r);
  return NmeaSentence(unknown(address, rest, has_fields));
}

NmeaError line_error(Code code, std::string message) {
  return NmeaError{code, std::move(message), 0};
}

}  // namespace

const char* to_string(NmeaError::Code code) {
  switch (code) {
    case Code::empty:
      return "empty";
    case Code::oversized:
      return "oversized";
    case Code::no_dollar:
      return "no_dollar";
    case Code::bad_character:
      return "bad_character";
    case Code::missing_checksum:
      return "missing_checksum";
    case Code::bad_checksum:
      return "bad_checksum";
    case Code::bad_address:
      return "bad_address";
    case Code::bad_field_count:
      return "bad_field_count";
    case Code::missing_field:
      return "missing_field";
    case Code::non_numeric:
      return "non_numeric";
    case Code::bad_value:
      return "bad_value";
    case Code::out_of_range:
      return "out_of_range";
  }
  return "?";
}

std::uint8_t nmea_checksum(std::string_view body) {
  std::uint8_t sum = 0;
  for (char c : body)
    sum ^= static_cast<std::uint8_t>(c);
  return sum;
}

std::optional<double> Gprmc::speed_mps() const {
  if (!speed_knots) return std::nullopt;
  return *speed_knots * kMetresPerSecondPerKnot;
}

std::optional<double> Gpvtg::speed_mps() const {
  if (!speed_knots) return std::nullopt;
  return *speed_knots * kMetresPerSecondPerKnot;
}

NmeaParseResult parse_sentence(std::string_view line, NmeaDirection direction) {
  NmeaParseResult result;
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r'))
    line.remove_suffix(1);
  if (line.empty()) {
    result.value = line_error(Code::empty, "empty line");
    return result;
  }
  if (line.size() > kNmeaMaxLineBytes) {
    result.value = line_error(Code::oversized, "line of " + std::to_string(line.size()) +
                                                   " bytes is longer than " +
                                                   std::to_string(kNmeaMaxLineBytes));
    return result;
  }
  if (line.front() != '$') {
    result.value = line_error(Code::no_dollar, "line does not start with '$'");
    return result;
  }

  std::size_t star = std::string_view::npos;
  std::uint8_t sum = 0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '*') {
      star = i;
      break;
    }
    if (c < 0x20 || c > 0x7e || c == '$') {
      char what[8];
      std::snprintf(what, sizeof what, "0x%02X",
                    static_cast<unsigned>(static_cast<unsigned char>(c)));
      result.value =
          line_error(Code::bad_character, std::string("byte ") + what + " at offset " +
                                              std::to_string(i) + " is not allowed in a sentence");
      return result;
    }
    sum ^= static_cast<std::uint8_t>(c);
  }

  const bool frontseat = direction == NmeaDirection::frontseat_to_backseat;
  const std::string_view body =
      line.substr(1, star == std::string_view::npos ? std::string_view::npos : star - 1);
  // A backseat line may come without its checksum; counting the three bytes it would take keeps
  // every accepted sentence writable again within the limit.
  if (body.size() > kNmeaMaxLineBytes - 4) {
    result.value = line_error(Code::oversized, "sentence of " + std::to_string(body.size() + 4) +
                                                   " bytes with its checksum is longer than " +
                                                   std::to_string(kNmeaMaxLineBytes));
    return result;
  }
  if (star == std::string_view::npos || star + 1 == line.size()) {
    result.checksum = star == std::string_view::npos ? NmeaChecksum::absent : NmeaChecksum::blank;
    if (frontseat) {
      result.value = line_error(Code::missing_checksum,
                                "no checksum: the frontseat always ends a sentence with *hh");
      return result;
    }
  } else {
    const std::string_view digits = line.substr(star + 1);
    const int high = digits.size() == 2 ? hex_value(digits[0]) : -1;
    const int low = digits.size() == 2 ? hex_value(digits[1]) : -1;
    if (high < 0 || low < 0) {
      result.value =
          line_error(Code::bad_checksum, "checksum " + quoted(digits) + " is not two hex digits");
      return result;
    }
    if (high * 16 + low != sum) {
      char expected[4];
      std::snprintf(expected, sizeof expected, "%02X", static_cast<unsigned>(sum));
      result.value =
          line_error(Code::bad_checksum,
                     "checksum " + quoted(digits) + " does not match the sentence's " + expected);
      return result;
    }
    const bool lower =
        (digits[0] >= 'a' && digits[0] <= 'f') || (digits[1] >= 'a' && digits[1] <= 'f');
    result.checksum = lower ? NmeaChecksum::lower_case : NmeaChecksum::upper_case;
  }
  result.value = parse_body(body);
  return result;
}

}  // namespace avk::vehicle
