#pragma once
// `$body*HH\r\n` with the right checksum: hand-written frontseat lines for tests.

#include <cstdio>
#include <string>
#include <string_view>

#include "vehicle/nmea.hpp"

namespace avk::testing {

inline std::string nmea_sentence(std::string_view body) {
  char sum[8];
  std::snprintf(sum, sizeof sum, "*%02X\r\n",
                static_cast<unsigned>(avk::vehicle::nmea_checksum(body)));
  std::string out = "$";
  out += body;
  out += sum;
  return out;
}

}  // namespace avk::testing
