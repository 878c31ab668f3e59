#include "vehicle/nmea_text.hpp"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <system_error>

namespace avk::vehicle::nmea {

namespace {

constexpr std::size_t kMaxQuoted = 24;

constexpr std::string_view kGnssTalkers[] = {"GP", "GN", "GL", "GA", "GB", "BD", "GQ", "GI"};

}  // namespace

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

bool is_gnss_talker(std::string_view talker) {
  for (std::string_view t : kGnssTalkers)
    if (t == talker) return true;
  return false;
}

}  // namespace avk::vehicle::nmea
