#pragma once
// Harvest runs over a mission's navigation (mission/turn_harvester.hpp) and what each found.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "store/store_error.hpp"

namespace avk::store {

// One harvest run: how many steps of the desired heading it judged, how many turns it stored, and
// the others by reason.
struct HarvestRecord {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  std::string created_utc;
  std::int64_t steps = 0;
  std::int64_t harvested = 0;
  std::int64_t already_recorded = 0;
  std::map<std::string, std::int64_t> rejected;  // reason -> count (reasons with a count only)
};

class HarvestRepository {
 public:
  virtual ~HarvestRepository() = default;

  // Returns the harvest id; h.id and h.created_utc are ignored.
  virtual std::int64_t save(const HarvestRecord& h) = 0;
  // The mission's harvest runs, oldest first.
  virtual std::vector<HarvestRecord> list(std::int64_t mission_id) = 0;
};

}  // namespace avk::store
