#include "vehicle/nav_ranges.hpp"

#include <charconv>
#include <system_error>

namespace avk::vehicle {

namespace {

std::string shortest_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return r.ec == std::errc() ? std::string(buf, r.ptr) : std::string("?");
}

}  // namespace

// Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "[" + std::string.
std::string to_string(const ValueRange& r) {
  std::string out = "[";
  out += shortest_text(r.low);
  out += ", ";
  out += shortest_text(r.high);
  out += r.open_high ? ")" : "]";
  return out;
}

}  // namespace avk::vehicle
