// libFuzzer target for the CKT file reader (parse_ckt_json), built by tests/CMakeLists.txt.
// Anything but ParseError escaping is a bug (nlohmann's exceptions included), and a table the
// reader accepts must be within the documented bounds, write back to the same text, and answer a
// query inside its speed range.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace avk::kinematics;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  Ckt table;
  try {
    table = parse_ckt_json(input);
  } catch (const ParseError& e) {
    if (e.field().empty() && e.message().empty()) std::abort();
    return 0;
  }
  const CktGrid& g = table.grid();
  if (g.speeds_mps.size() > kCktMaxGridSpeeds || g.dheadings_deg.size() > kCktMaxGridDheadings)
    std::abort();
  for (double u : g.speeds_mps)
    if (!(u > 0.0 && u <= kCktMaxSpeedMps)) std::abort();
  const std::string text = ckt_to_json_string(table);
  if (ckt_to_json_string(parse_ckt_json(text)) != text) std::abort();
  if (const auto range = table.speed_range_mps()) {
    try {
      const TurnPrediction p = table.query(0.5 * (range->first + range->second), 45.0);
      if (!std::isfinite(p.advance_m) || !std::isfinite(p.transfer_m)) std::abort();
    } catch (const CktRangeError&) {
      // A speed row without the heading changes asked for may refuse; it must say so this way.
    }
  }
  return 0;
}
