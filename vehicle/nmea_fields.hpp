#pragma once
// Splitting a sentence into its fields and reading them as typed values: the one place that
// states how each kind of field (number, heading, integer, flag, time, date, coordinate) looks on
// the wire and which error a bad one is.

#include <array>
#include <charconv>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "vehicle/nav_ranges.hpp"
#include "vehicle/nmea.hpp"
#include "vehicle/nmea_text.hpp"

namespace avk::vehicle::nmea {

using Code = NmeaError::Code;
using Range = ValueRange;

constexpr std::size_t kMaxTypedFields = 16;  // more than any typed sentence has

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

}  // namespace avk::vehicle::nmea
