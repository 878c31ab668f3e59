#include "store/sql/sql_harvests.hpp"

#include <exception>
#include <utility>

#include <nlohmann/json.hpp>

#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kHarvest = columns("id", "mission_id", "created_utc", "steps", "harvested",
                                  "already_recorded", "rejected_json");

HarvestRecord read_harvest(const Statement& s) {
  HarvestRecord h;
  h.id = s.column_int64(kHarvest["id"]);
  h.mission_id = s.column_int64(kHarvest["mission_id"]);
  h.created_utc = s.column_text(kHarvest["created_utc"]);
  h.steps = s.column_int64(kHarvest["steps"]);
  h.harvested = s.column_int64(kHarvest["harvested"]);
  h.already_recorded = s.column_int64(kHarvest["already_recorded"]);
  try {
    h.rejected = nlohmann::json::parse(s.column_text(kHarvest["rejected_json"]))
                     .get<std::map<std::string, std::int64_t>>();
  } catch (const std::exception& e) {
    throw StoreError("harvest " + std::to_string(h.id) +
                     ": stored rejected_json is corrupt: " + e.what());
  }
  return h;
}

}  // namespace

std::int64_t SqlHarvests::save(const HarvestRecord& h) {
  auto s = db_.prepare(
      "INSERT INTO harvests (mission_id, steps, harvested, already_recorded, rejected_json) "
      "VALUES (?, ?, ?, ?, ?) RETURNING id");
  s.bind(1, h.mission_id).bind(2, h.steps).bind(3, h.harvested).bind(4, h.already_recorded);
  s.bind(5, nlohmann::json(h.rejected).dump());
  return inserted_id(s);
}

std::vector<HarvestRecord> SqlHarvests::list(std::int64_t mission_id) {
  auto s =
      db_.prepare("SELECT " + kHarvest.list() + " FROM harvests WHERE mission_id = ? ORDER BY id");
  s.bind(1, mission_id);
  std::vector<HarvestRecord> out;
  while (s.step())
    out.push_back(read_harvest(s));
  return out;
}

}  // namespace avk::store::sql
