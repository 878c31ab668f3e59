#include "app/harvest.hpp"

#include <nlohmann/json.hpp>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "mission/mission_config.hpp"
#include "mission/turn_harvester.hpp"
#include "store/store.hpp"

namespace avk::app {

namespace {

// The rules the mission's turns were judged by: its own ConditionSet and completion rule, or
// for an imported log the numbers the import used, or the defaults.
mission::HarvestOptions options_for(const store::Mission& m) {
  mission::HarvestOptions o;
  auto& x = o.extraction;
  try {
    const auto config = mission::parse_mission_config(m.config_json, 1e9);
    x.condition_set = config.condition_set;
    x.completion = config.completion;
    x.turn_timeout_s = config.turn_timeout_s;
    return o;
  } catch (const std::exception&) {
    // Not a mission file: an import (docs/alog-import.md) or something older.
  }
  const auto doc = nlohmann::json::parse(m.config_json, nullptr, false);
  if (!doc.is_object() || !doc.contains("extraction") || !doc["extraction"].is_object()) return o;
  const auto& e = doc["extraction"];
  const auto number = [&](const char* key, double fallback) {
    return e.contains(key) && e[key].is_number() ? e[key].get<double>() : fallback;
  };
  x.min_step_deg = number("min_step_deg", x.min_step_deg);
  x.completion.threshold_deg = number("completion_threshold_deg", x.completion.threshold_deg);
  x.completion.fraction = number("completion_fraction", x.completion.fraction);
  x.completion.floor_deg = number("completion_floor_deg", x.completion.floor_deg);
  x.condition_set.speed_tolerance_mps =
      number("speed_tolerance_mps", x.condition_set.speed_tolerance_mps);
  x.condition_set.max_yaw_rate_dps = number("max_yaw_rate_dps", x.condition_set.max_yaw_rate_dps);
  x.condition_set.window = static_cast<int>(number("window", x.condition_set.window));
  x.max_gap_s = number("max_gap_s", x.max_gap_s);
  return o;
}

HarvestReport harvest(store::Store& db, const store::Mission& m) {
  const auto rows = db.navigation().for_mission(m.id);
  const auto recorded = db.turns().start_times(m.id);
  const auto log = guided_log(rows);
  const auto result =
      mission::harvest_turns(log, recorded, options_for(m), m.vehicle_id, std::to_string(m.id));
  HarvestReport r;
  r.mission_id = m.id;
  r.vehicle_id = m.vehicle_id;
  r.nav_rows = rows.size();
  r.steps = result.steps;
  r.already_recorded = result.already_recorded;
  r.rejected = result.rejected_total();
  store::HarvestRecord record;
  record.mission_id = m.id;
  record.steps = static_cast<std::int64_t>(result.steps);
  record.already_recorded = static_cast<std::int64_t>(result.already_recorded);
  for (std::size_t i = 0; i < mission::kStepRejectionCount; ++i) {
    const std::string reason(mission::kStepRejectionNames[i]);
    r.rejected_by_reason[reason] = result.rejected[i];
    if (result.rejected[i] > 0)
      record.rejected[reason] = static_cast<std::int64_t>(result.rejected[i]);
  }
  double quality_sum = 0.0;
  for (const auto& h : result.turns) {
    store::TurnStart start;
    start.yaw_rate_dps = h.start.yaw_rate_dps;
    r.turn_ids.push_back(db.turns().add(m.id, h.turn, kinematics::TurnStatus::ok, "", start));
    quality_sum += h.turn.meta().quality.value_or(0.0);
  }
  r.harvested = r.turn_ids.size();
  if (r.harvested > 0) r.mean_quality = quality_sum / static_cast<double>(r.harvested);
  record.harvested = static_cast<std::int64_t>(r.harvested);
  r.harvest_id = db.harvests().save(record);
  return r;
}

}  // namespace

Result<HarvestReport> harvest_mission(Context& ctx, std::int64_t mission_id) {
  store::Store& db = store_of(ctx);
  const auto m = db.missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id));
  return harvest(db, *m);
}

Result<std::vector<HarvestReport>> harvest_vehicle(Context& ctx, const std::string& vehicle_id) {
  store::Store& db = store_of(ctx);
  std::vector<HarvestReport> out;
  for (const auto& m : db.missions().list())
    if (m.vehicle_id == vehicle_id) out.push_back(harvest(db, m));
  if (out.empty()) return not_found("vehicle '" + vehicle_id + "' has no missions");
  return out;
}

}  // namespace avk::app
