// libFuzzer target for the mission file reader (parse_mission_config), built by
// tests/CMakeLists.txt. Only MissionConfigError may leave it, each error naming a field; an
// accepted mission is within the documented limits, so planning it is bounded.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace avk::mission;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  MissionConfig c;
  try {
    c = parse_mission_config(input, 2.0);
  } catch (const MissionConfigError& e) {
    if (e.errors().empty()) std::abort();
    for (const auto& f : e.errors())
      if (f.field.empty() || f.message.empty()) std::abort();
    return 0;
  }
  if (c.turn_array.speeds_mps.size() > kMaxMissionSpeeds ||
      c.turn_array.dheadings_deg.size() > kMaxMissionDheadings ||
      c.region.polygon.size() > kMaxRegionVertices || c.region.polygon.size() < 3)
    std::abort();
  if (plan_turns(c).size() > kMaxPlannedTurns) std::abort();
  if (!polygon_is_simple(c.region.polygon)) std::abort();
  return 0;
}
