// libFuzzer target for the two turn record parsers (not built by CMake yet: it needs clang).
//   clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -I. -o turn_record_fuzz
//     tests/fuzz/turn_record_fuzz.cpp kinematics/turn_text.cpp kinematics/turn_json.cpp
//     kinematics/turn_sequence.cpp kinematics/geometry.cpp
// Any exception other than ParseError, a sanitizer report or a failed round trip is a bug.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/turn_text.hpp"

namespace {

using avk::kinematics::ParseError;
using avk::kinematics::TurnSequence;

// Whatever a parser accepts must write back and read again to the same turn: an accepted input
// that cannot be written (say a NaN slipping through) is as much a bug as a crash.
template <class Parse, class Write>
void check(std::string_view input, Parse parse, Write write) {
  TurnSequence turn;
  try {
    turn = parse(input);
  } catch (const ParseError&) {
    return;
  }
  const std::string again = write(turn);
  const TurnSequence back = parse(again);
  if (!(back == turn) || back.warnings() != turn.warnings() || write(back) != again) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  check(input, avk::kinematics::parse_text_record, avk::kinematics::to_text_record);
  check(input, avk::kinematics::parse_turn_json, avk::kinematics::to_json_string);
  return 0;
}
