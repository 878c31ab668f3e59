#pragma once
// Harvesting turns from a stored mission's navigation: every step of the
// desired heading judged by the rules of a measured turn (mission/turn_harvester.hpp); the
// accepted ones stored with the mission as source=harvested with their quality, the run
// recorded with its counts. docs/harvest.md.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "vehicle/alog.hpp"

namespace avk::app {

class Context;

struct HarvestReport {
  std::int64_t mission_id = 0;
  std::string vehicle_id;
  std::int64_t harvest_id = 0;  // the run's record in the store
  std::size_t nav_rows = 0;
  std::size_t steps = 0;             // steps of the desired heading judged
  std::size_t harvested = 0;         // turns stored
  std::size_t already_recorded = 0;  // steps whose turn the mission already held
  std::size_t rejected = 0;
  std::map<std::string, std::size_t> rejected_by_reason;  // every reason of the fixed list
  std::vector<std::int64_t> turn_ids;
  double mean_quality = 0.0;  // over the turns stored (0 without any)
};

// not_found for an unknown mission.
Result<HarvestReport> harvest_mission(Context& ctx, std::int64_t mission_id);
// Every mission of the vehicle, oldest first (not_found when it has none).
Result<std::vector<HarvestReport>> harvest_vehicle(Context& ctx, const std::string& vehicle_id);

}  // namespace avk::app
