// libFuzzer target for the frontseat protocol parser (built by CMake when clang++ is found).
//   clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -I. -o nmea_fuzz
//     tests/fuzz/nmea_fuzz.cpp vehicle/nmea.cpp
//   ./nmea_fuzz -runs=10000000 -max_len=300
// The parser must never throw, and whatever it accepts must write back (format_sentence) and
// read again to the same sentence type, the written text a fixed point: an accepted input that
// cannot be written (a NaN slipping through, a range check missed) is as much a bug as a crash.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "vehicle/nmea.hpp"

namespace {

using avk::vehicle::NmeaDirection;
using avk::vehicle::NmeaParseResult;

void check(std::string_view input, NmeaDirection direction) {
  const NmeaParseResult r = avk::vehicle::parse_sentence(input, direction);
  if (r.value.valueless_by_exception()) std::abort();
  if (const auto* e = r.error()) {
    if (e->message.empty() || e->field > 16) std::abort();
    return;
  }
  const std::string again = avk::vehicle::format_sentence(*r.sentence());
  const NmeaParseResult back =
      avk::vehicle::parse_sentence(again, NmeaDirection::frontseat_to_backseat);
  if (!back.ok() || back.sentence()->index() != r.sentence()->index()) std::abort();
  if (avk::vehicle::format_sentence(*back.sentence()) != again) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  check(input, NmeaDirection::frontseat_to_backseat);
  check(input, NmeaDirection::backseat_to_frontseat);
  return 0;
}
