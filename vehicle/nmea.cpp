#include "vehicle/nmea.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "vehicle/nav_ranges.hpp"

namespace avk::vehicle {

namespace {

using Code = NmeaError::Code;

// Navigation ranges are the ones every reader of navigation shares (vehicle/nav_ranges.hpp).
// Beyond the protocol's own limits (thrust, latitudes), the bounds of the others are far outside
// anything a small boat reports: they catch garbage that passed the checksum (a firmware bug, a
// corrupted but consistent relay), not unusual motion.
using Range = ValueRange;

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

constexpr std::size_t kMaxTypedFields = 16;  // more than any typed sentence has
constexpr std::size_t kMaxQuoted = 24;

constexpr std::string_view kGnssTalkers[] = {"GP", "GN", "GL", "GA", "GB", "BD", "GQ", "GI"};

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

bool all_digits(std::string_view s) {
  for (char c : s)
    if (!is_digit(c)) return false;
  return !s.empty();
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// A garbage field must not flood a message with 200 bytes.
std::string quoted(std::string_view s) {
  std::string out = "'";
  out += s.substr(0, kMaxQuoted);
  if (s.size() > kMaxQuoted) out += "...";
  out += "'";
  return out;
}

std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return r.ec == std::errc() ? std::string(buf, r.ptr) : std::string("?");
}

// Decimal numbers as the protocol writes them: an optional sign, digits, an optional fraction.
// No exponent, no inf or nan: from_chars alone would take those.
std::optional<double> decimal(std::string_view s) {
  std::string_view digits = s;
  if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) digits.remove_prefix(1);
  bool any_digit = false;
  bool point = false;
  for (char c : digits) {
    if (is_digit(c)) {
      any_digit = true;
    } else if (c == '.' && !point) {
      point = true;
    } else {
      return std::nullopt;
    }
  }
  if (!any_digit) return std::nullopt;
  // from_chars takes a leading minus but not a plus.
  const std::string_view text = s.front() == '+' ? digits : s;
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

// The fields after the sentence id, 1-based. Only sentences with at most kMaxTypedFields fields
// are split here: longer ones are either unknown (split into strings) or a wrong field count.
class Fields {
 public:
  explicit Fields(std::string_view rest, bool has_fields) {
    if (!has_fields) return;
    count_ = 1;
    for (char c : rest)
      count_ += c == ',' ? 1 : 0;
    if (count_ > kMaxTypedFields) return;
    std::size_t i = 0;
    for (;;) {
      const std::size_t comma = rest.find(',');
      fields_[i++] = rest.substr(0, comma);
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
  }
  std::size_t size() const { return count_; }
  std::string_view operator[](std::size_t i) const {
    return i >= 1 && i <= count_ && count_ <= kMaxTypedFields ? fields_[i - 1] : std::string_view();
  }

 private:
  std::size_t count_ = 0;
  std::array<std::string_view, kMaxTypedFields> fields_;
};

// Reads typed fields and keeps the first problem: a sentence parser reads every field in turn and
// checks once at the end, and every read after a failure is a no-op returning a default.
class Reader {
 public:
  Reader(std::string_view address, const Fields& fields) : address_(address), fields_(fields) {}

  bool failed() const { return error_.has_value(); }
  NmeaError take_error() { return std::move(*error_); }

  bool expect_count(std::initializer_list<std::size_t> counts) {
    for (std::size_t n : counts)
      if (fields_.size() == n) return true;
    std::string expected;
    for (std::size_t n : counts) {
      if (!expected.empty()) expected += " or ";
      expected += std::to_string(n);
    }
    error_ = NmeaError{Code::bad_field_count,
                       std::string(address_) + " has " + std::to_string(fields_.size()) +
                           " fields, expected " + expected,
                       0};
    return false;
  }

  std::size_t count() const { return fields_.size(); }
  std::string_view text(std::size_t i) const { return fields_[i]; }

  std::optional<double> maybe_number(std::size_t i, const char* name, const Range& range) {
    if (failed() || text(i).empty()) return std::nullopt;
    const auto v = decimal(text(i));
    if (!v) {
      fail(Code::non_numeric, i, name, quoted(text(i)) + " is not a decimal number");
      return std::nullopt;
    }
    if (!range.contains(*v)) {
      fail(Code::out_of_range, i, name, quoted(text(i)) + " is out of range " + to_string(range));
      return std::nullopt;
    }
    return v;
  }

  double number(std::size_t i, const char* name, const Range& range) {
    return require(maybe_number(i, name, range), i, name).value_or(0.0);
  }

  // Degrees true. Exactly 360 reads as 0: a frontseat rounding 359.9999997 to six decimals
  // writes it, and dropping a navigation sample over that would be worse than wrapping it.
  std::optional<double> maybe_heading(std::size_t i, const char* name) {
    const auto v = maybe_number(i, name, kHeadingRange_deg);
    if (v && *v == 360.0) return 0.0;
    return v;
  }

  double heading(std::size_t i, const char* name) {
    return require(maybe_heading(i, name), i, name).value_or(0.0);
  }

  std::optional<int> maybe_integer(std::size_t i, const char* name, int low, int high) {
    if (failed() || text(i).empty()) return std::nullopt;
    const std::string_view s = text(i);
    const bool negative = s.front() == '-';
    if (!all_digits(negative ? s.substr(1) : s)) {
      fail(Code::non_numeric, i, name, quoted(s) + " is not an integer");
      return std::nullopt;
    }
    int v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || v < low || v > high) {
      fail(Code::out_of_range, i, name,
           quoted(s) + " is out of range [" + std::to_string(low) + ", " + std::to_string(high) +
               "]");
      return std::nullopt;
    }
    return v;
  }

  int integer(std::size_t i, const char* name, int low, int high) {
    return require(maybe_integer(i, name, low, high), i, name).value_or(0);
  }

  // One character out of allowed.
  std::optional<char> maybe_flag(std::size_t i, const char* name, std::string_view allowed) {
    if (failed() || text(i).empty()) return std::nullopt;
    const std::string_view s = text(i);
    if (s.size() != 1 || allowed.find(s.front()) == std::string_view::npos) {
      std::string options;
      for (char c : allowed) {
        if (!options.empty()) options += '|';
        options += c;
      }
      fail(Code::bad_value, i, name, quoted(s) + " is not one of " + options);
      return std::nullopt;
    }
    return s.front();
  }

  char flag(std::size_t i, const char* name, std::string_view allowed) {
    return require(maybe_flag(i, name, allowed), i, name).value_or(allowed.front());
  }

  // hhmmss or hhmmss.s..., as seconds since midnight. Seconds run to 60.999 for a leap second.
  std::optional<double> maybe_time(std::size_t i, const char* name) {
    if (failed() || text(i).empty()) return std::nullopt;
    const std::string_view s = text(i);
    const std::size_t point = s.find('.');
    const std::string_view whole = s.substr(0, point);
    const std::string_view fraction =
        point == std::string_view::npos ? std::string_view() : s.substr(point + 1);
    if (!all_digits(whole) ||
        (point != std::string_view::npos && !fraction.empty() && !all_digits(fraction))) {
      fail(Code::non_numeric, i, name, quoted(s) + " is not a time hhmmss.sss");
      return std::nullopt;
    }
    if (whole.size() != 6) {
      fail(Code::bad_value, i, name, quoted(s) + " is not a time hhmmss.sss");
      return std::nullopt;
    }
    const int hours = (whole[0] - '0') * 10 + (whole[1] - '0');
    const int minutes = (whole[2] - '0') * 10 + (whole[3] - '0');
    const auto seconds = decimal(s.substr(4));
    if (hours > 23 || minutes > 59 || !seconds || *seconds >= 61.0) {
      fail(Code::out_of_range, i, name, quoted(s) + " is not a time of day");
      return std::nullopt;
    }
    return hours * 3600.0 + minutes * 60.0 + *seconds;
  }

  double time(std::size_t i, const char* name) {
    return require(maybe_time(i, name), i, name).value_or(0.0);
  }

  // ddmmyy; two-digit years 80-99 are 19yy (GPS began in 1980), others 20yy.
  std::optional<NmeaDate> maybe_date(std::size_t i, const char* name) {
    if (failed() || text(i).empty()) return std::nullopt;
    const std::string_view s = text(i);
    if (!all_digits(s)) {
      fail(Code::non_numeric, i, name, quoted(s) + " is not a date ddmmyy");
      return std::nullopt;
    }
    if (s.size() != 6) {
      fail(Code::bad_value, i, name, quoted(s) + " is not a date ddmmyy");
      return std::nullopt;
    }
    NmeaDate d;
    d.day = (s[0] - '0') * 10 + (s[1] - '0');
    d.month = (s[2] - '0') * 10 + (s[3] - '0');
    const int yy = (s[4] - '0') * 10 + (s[5] - '0');
    d.year = yy >= 80 ? 1900 + yy : 2000 + yy;
    constexpr int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (d.year % 4 == 0 && d.year % 100 != 0) || d.year % 400 == 0;
    if (d.month < 1 || d.month > 12 || d.day < 1 || d.day > kDays[d.month - 1] ||
        (d.month == 2 && d.day == 29 && !leap)) {
      fail(Code::out_of_range, i, name, quoted(s) + " is not a calendar date");
      return std::nullopt;
    }
    return d;
  }

  // A latitude (ddmm.mmmm) or longitude (dddmm.mmmm, zero-padded or not) in field i and its
  // hemisphere letter in field i + 1, as signed degrees. Blank is no position.
  std::optional<double> maybe_coordinate(std::size_t i, bool latitude) {
    const char* name = latitude ? "latitude" : "longitude";
    const char* hemisphere_name = latitude ? "latitude hemisphere" : "longitude hemisphere";
    const std::string_view hemispheres = latitude ? "NS" : "EW";
    if (failed()) return std::nullopt;
    const std::string_view s = text(i);
    if (s.empty()) {
      maybe_flag(i + 1, hemisphere_name, hemispheres);  // still checked when present
      return std::nullopt;
    }
    if (s.front() == '-' || s.front() == '+') {
      fail(Code::bad_value, i, name,
           quoted(s) + " is signed; the hemisphere letter gives the sign");
      return std::nullopt;
    }
    if (!decimal(s)) {
      fail(Code::non_numeric, i, name, quoted(s) + " is not a decimal number");
      return std::nullopt;
    }
    // The last two digits before the point start the minutes; the rest are degrees.
    const std::size_t point = std::min(s.find('.'), s.size());
    const std::size_t split = point >= 2 ? point - 2 : 0;
    const double degrees = split == 0 ? 0.0 : decimal(s.substr(0, split)).value_or(1e9);
    const double minutes = decimal(s.substr(split)).value_or(1e9);
    const double limit = latitude ? 90.0 : 180.0;
    if (minutes >= 60.0) {
      fail(Code::out_of_range, i, name, quoted(s) + " has minutes of 60 or more");
      return std::nullopt;
    }
    const double value = degrees + minutes / 60.0;
    if (value > limit) {
      fail(Code::out_of_range, i, name,
           quoted(s) + " is beyond " + number_text(limit) + " degrees");
      return std::nullopt;
    }
    const char h = require(maybe_flag(i + 1, hemisphere_name, hemispheres), i + 1, hemisphere_name)
                       .value_or('N');
    if (failed()) return std::nullopt;
    return h == 'S' || h == 'W' ? -value : value;
  }

  // Latitude in fields i, i + 1 and longitude in i + 2, i + 3: both or neither.
  void position(std::size_t i, bool required, std::optional<double>& lat,
                std::optional<double>& lon) {
    lat = maybe_coordinate(i, true);
    lon = maybe_coordinate(i + 2, false);
    if (failed()) return;
    if (!lat && (required || lon)) {
      fail(Code::missing_field, i, "latitude", "is blank");
    } else if (!lon && (required || lat)) {
      fail(Code::missing_field, i + 2, "longitude", "is blank");
    }
  }

  // A unit letter (the M after an altitude, the T after a course): the one letter, or blank.
  void unit(std::size_t i, const char* name, char letter) {
    maybe_flag(i, name, std::string_view(&letter, 1));
  }

  void fail(Code code, std::size_t i, const char* name, const std::string& what) {
    if (failed()) return;
    error_ = NmeaError{
        code, std::string(address_) + " field " + std::to_string(i) + " (" + name + "): " + what,
        i};
  }

 private:
  template <class T>
  std::optional<T> require(std::optional<T> v, std::size_t i, const char* name) {
    if (!v && !failed()) fail(Code::missing_field, i, name, "is blank");
    return v;
  }

  std::string_view address_;
  const Fields& fields_;
  std::optional<NmeaError> error_;
};

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

bool is_gnss_talker(std::string_view talker) {
  for (std::string_view t : kGnssTalkers)
    if (t == talker) return true;
  return false;
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

// ---- Formatting -----------------------------------------------------------------------------

namespace {

// Builds `$ADDRESS,f1,...*HH\r\n`. Values it cannot represent faithfully are written so that the
// check in format_checked rejects them with the field's name: non-finite as nan/inf, magnitudes
// beyond every range in exponent form (never valid on the wire).
class Writer {
 public:
  explicit Writer(std::string_view address) {
    out_.reserve(128);
    out_ += '$';
    out_ += address;
  }

  Writer& blank() {
    out_ += ',';
    return *this;
  }

  Writer& text(std::string_view s) {
    out_ += ',';
    out_ += s;
    return *this;
  }

  Writer& letter(char c) {
    out_ += ',';
    out_ += c;
    return *this;
  }

  Writer& integer(long long v) { return text(std::to_string(v)); }

  Writer& number(double v) {
    out_ += ',';
    append_number(v);
    return *this;
  }

  Writer& number(const std::optional<double>& v) { return v ? number(*v) : blank(); }

  Writer& heading(double v) {
    out_ += ',';
    const std::size_t at = out_.size();
    append_number(v);
    if (std::string_view(out_).substr(at) == "360") out_.replace(at, 3, "0");
    return *this;
  }

  Writer& heading(const std::optional<double>& v) { return v ? heading(*v) : blank(); }

  // hhmmss with up to six decimals of seconds. Times past midnight wrap: an emulator may count
  // seconds since it started.
  Writer& time(double t_s, const char* what) {
    if (!std::isfinite(t_s) || t_s < 0.0 || t_s > 1e12)
      throw std::invalid_argument(std::string(what) + " " + number_text(t_s) +
                                  " is not a time of day in seconds");
    constexpr long long kDay_us = 86400LL * 1000000LL;
    const long long us = std::llround(t_s * 1e6) % kDay_us;
    const long long s = us / 1000000;
    char buf[32];
    std::snprintf(buf, sizeof buf, ",%02lld%02lld%02lld", s / 3600, s / 60 % 60, s % 60);
    out_ += buf;
    append_fraction(us % 1000000);
    return *this;
  }

  Writer& time(const std::optional<double>& t_s, const char* what) {
    return t_s ? time(*t_s, what) : blank();
  }

  // ddmm.mmmmmm,N or dddmm.mmmmmm,E: the minutes rounded to six decimals in integers, so that
  // 59.9999999' carries into the degrees instead of being written 60.
  Writer& coordinate(double deg, bool latitude, bool pad) {
    const double limit = latitude ? 90.0 : 180.0;
    if (!std::isfinite(deg) || std::abs(deg) > limit)
      throw std::invalid_argument(std::string(latitude ? "latitude " : "longitude ") +
                                  number_text(deg) + " is out of range [-" + number_text(limit) +
                                  ", " + number_text(limit) + "]");
    const long long micro_minutes = std::llround(std::abs(deg) * 60e6);
    const long long degrees = micro_minutes / 60000000;
    const long long rest = micro_minutes % 60000000;
    char buf[32];
    if (latitude) {
      std::snprintf(buf, sizeof buf, ",%02lld%02lld", degrees, rest / 1000000);
    } else {
      std::snprintf(buf, sizeof buf, pad ? ",%03lld%02lld" : ",%lld%02lld", degrees,
                    rest / 1000000);
    }
    out_ += buf;
    append_fraction(rest % 1000000);
    const bool negative = deg < 0.0 && micro_minutes != 0;
    return letter(latitude ? (negative ? 'S' : 'N') : (negative ? 'W' : 'E'));
  }

  Writer& position(const std::optional<double>& lat, const std::optional<double>& lon, bool pad) {
    if (lat.has_value() != lon.has_value())
      throw std::invalid_argument("latitude and longitude must be both given or both blank");
    if (!lat) return blank().blank().blank().blank();
    return coordinate(*lat, true, pad).coordinate(*lon, false, pad);
  }

  std::string finish() {
    const std::uint8_t sum = nmea_checksum(std::string_view(out_).substr(1));
    char buf[8];
    std::snprintf(buf, sizeof buf, "*%02X\r\n", static_cast<unsigned>(sum));
    out_ += buf;
    return std::move(out_);
  }

 private:
  void append_number(double v) {
    char buf[64];
    const auto fmt = std::isfinite(v) && std::abs(v) < 1e9 ? std::chars_format::fixed
                                                           : std::chars_format::scientific;
    auto r = std::to_chars(buf, buf + sizeof buf, v, fmt, 6);
    std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
    if (fmt == std::chars_format::fixed && s.find('.') != std::string_view::npos) {
      while (s.back() == '0')
        s.remove_suffix(1);
      if (s.back() == '.') s.remove_suffix(1);
    }
    if (s == "-0") s = "0";
    out_ += s;
  }

  // A fraction in millionths as .dddddd, trailing zeros stripped, nothing for zero.
  void append_fraction(long long millionths) {
    if (millionths == 0) return;
    char buf[16];
    std::snprintf(buf, sizeof buf, ".%06lld", millionths);
    std::string_view s(buf);
    while (s.back() == '0')
      s.remove_suffix(1);
    out_ += s;
  }

  std::string out_;
};

std::string date_text(const NmeaDate& d) {
  if (d.year < 1980 || d.year > 2079)
    throw std::invalid_argument("date year " + std::to_string(d.year) +
                                " is outside 1980-2079, which ddmmyy can hold");
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d%02d%02d", std::clamp(d.day, 0, 99),
                std::clamp(d.month, 0, 99), d.year % 100);
  return buf;
}

std::string talker_of(const std::string& talker) {
  if (!is_gnss_talker(talker))
    throw std::invalid_argument("talker " + quoted(talker) + " is not a GNSS talker");
  return talker;
}

std::string write(const Cpnvg& s) {
  Writer w("CPNVG");
  w.time(s.time_s, "time").coordinate(s.lat_deg, true, false).coordinate(s.lon_deg, false, false);
  w.letter(s.position_ok ? '1' : '0').number(s.altitude_m).number(s.depth_m);
  w.heading(s.heading_deg).number(s.roll_deg).number(s.pitch_deg).time(s.nav_time_s, "nav time");
  return w.finish();
}

std::string write(const Cpnvr& s) {
  Writer w("CPNVR");
  w.time(s.time_s, "time").number(s.v_east_mps).number(s.v_north_mps).number(s.v_down_mps);
  w.number(s.pitch_rate_dps).number(s.roll_rate_dps).number(s.yaw_rate_dps);
  return w.finish();
}

std::string write(const Cprbs& s) {
  Writer w("CPRBS");
  w.time(s.time_s, "time");
  if (s.battery_id) w.integer(*s.battery_id);
  w.number(s.stack_v).number(s.min_v).number(s.max_v).number(s.temperature_c);
  return w.finish();
}

std::string write(const Cprcm& s) {
  Writer w("CPRCM");
  w.time(s.time_s, "time").integer(s.compass_id).heading(s.heading_deg);
  w.number(s.pitch_deg).number(s.roll_deg).time(s.imu_time_s, "imu time");
  return w.finish();
}

std::string write(const Cpimu& s) {
  Writer w("CPIMU");
  w.time(s.time_s, "time").number(s.rate_x_dps).number(s.rate_y_dps).number(s.rate_z_dps);
  w.number(s.accel_x).number(s.accel_y).number(s.accel_z);
  return w.finish();
}

std::string write(const Cpalt& s) {
  Writer w("CPALT");
  w.time(s.time_s, "time").number(s.value);
  return w.finish();
}

std::string write(const Gprmc& s) {
  Writer w(talker_of(s.talker) + "RMC");
  w.time(s.time_s, "time").letter(s.valid ? 'A' : 'V').position(s.lat_deg, s.lon_deg, true);
  w.number(s.speed_knots).heading(s.course_deg);
  if (s.date) {
    w.text(date_text(*s.date));
  } else {
    w.blank();
  }
  if (s.magnetic_variation_deg) {
    w.number(std::abs(*s.magnetic_variation_deg))
        .letter(*s.magnetic_variation_deg < 0.0 ? 'W' : 'E');
  } else {
    w.blank().blank();
  }
  // The mode is written when either later field is: the status cannot come without it.
  if (s.mode || s.nav_status) {
    if (s.mode) {
      w.letter(*s.mode);
    } else {
      w.blank();
    }
  }
  if (s.nav_status) w.letter(*s.nav_status);
  return w.finish();
}

std::string write(const Gpgga& s) {
  Writer w(talker_of(s.talker) + "GGA");
  w.time(s.time_s, "time").position(s.lat_deg, s.lon_deg, true).integer(s.quality);
  if (s.satellites) {
    w.integer(*s.satellites);
  } else {
    w.blank();
  }
  w.number(s.hdop).number(s.altitude_m).letter('M').number(s.geoid_separation_m).letter('M');
  w.number(s.dgps_age_s);
  if (s.dgps_station) {
    w.integer(*s.dgps_station);
  } else {
    w.blank();
  }
  return w.finish();
}

std::string write(const Gpvtg& s) {
  Writer w(talker_of(s.talker) + "VTG");
  w.heading(s.course_true_deg).letter('T').heading(s.course_magnetic_deg).letter('M');
  w.number(s.speed_knots).letter('N').number(s.speed_kmh).letter('K');
  if (s.mode) w.letter(*s.mode);
  return w.finish();
}

std::string write(const Pydir& s) {
  Writer w("PYDIR");
  w.number(s.left_pct).number(s.right_pct);
  return w.finish();
}

std::string write(const Pydev& s) {
  Writer w("PYDEV");
  w.heading(s.heading_deg).number(s.speed_mps);
  return w.finish();
}

std::string write(const Pydep& s) {
  Writer w("PYDEP");
  w.number(s.yaw_rate_dps).number(s.thrust_pct);
  return w.finish();
}

std::string write(const Pyclt& s) {
  Writer w("PYCLT");
  w.letter(s.lights_on ? '1' : '0');
  return w.finish();
}

std::string write(const UnknownSentence& s) {
  Writer w(s.address);
  for (const std::string& f : s.fields) {
    if (f.find_first_of(",*") != std::string::npos)
      throw std::invalid_argument("field " + quoted(f) + " holds a ',' or '*'");
    w.text(f);
  }
  return w.finish();
}

// Writes a sentence and reads it back: the parser is the one statement of the protocol's
// ranges, so what it would reject never leaves the sender.
template <class T>
std::string format_checked(const T& s, const char* what) {
  std::string line;
  try {
    line = write(s);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(what) + ": " + e.what());
  }
  const NmeaParseResult back = parse_sentence(line, NmeaDirection::frontseat_to_backseat);
  if (const NmeaError* e = back.error())
    throw std::invalid_argument(std::string(what) + ": " + e->message);
  if (!std::holds_alternative<T>(*back.sentence()))
    throw std::invalid_argument(std::string(what) + ": " + quoted(line) +
                                " reads back as another sentence type");
  return line;
}

}  // namespace

std::string format_sentence(const NmeaSentence& sentence) {
  return std::visit([](const auto& s) { return format_checked(s, "format_sentence"); }, sentence);
}

std::string format_pydir(double left_pct, double right_pct) {
  return format_checked(Pydir{left_pct, right_pct}, "format_pydir");
}

std::string format_cpnvg(const Cpnvg& s) {
  return format_checked(s, "format_cpnvg");
}

std::string format_cpnvr(const Cpnvr& s) {
  return format_checked(s, "format_cpnvr");
}

std::string format_cprbs(const Cprbs& s) {
  return format_checked(s, "format_cprbs");
}

std::string format_gprmc(const Gprmc& s) {
  return format_checked(s, "format_gprmc");
}

}  // namespace avk::vehicle
