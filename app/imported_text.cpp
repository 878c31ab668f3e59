#include "app/imported_text.hpp"

#include <string>

#include "kinematics/text_limit.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

namespace {

// The refusal of one field: "avk.mission metadata 'name' must be at most ...".
Status refused(const std::string& what, const std::string& why) {
  return invalid_argument("file", what + " " + why);
}

}  // namespace

Status check_imported_text(const store::MissionImport& d) {
  using kinematics::text_too_long;
  if (const auto why = text_too_long(d.mission.name, mission::kMaxMissionNameBytes))
    return refused("avk.mission metadata 'name'", *why);
  if (const auto why = text_too_long(d.mission.status_reason, kMaxReasonBytes))
    return refused("avk.mission metadata 'status_reason'", *why);
  if (const auto why = vehicle::vehicle_id_problem(d.mission.vehicle_id))
    return refused("avk.mission metadata 'vehicle_id'", *why);
  if (const auto why = vehicle::vehicle_id_problem(d.vehicle.id))
    return refused("avk.vehicle metadata 'id'", *why);
  if (const auto why = text_too_long(d.vehicle.kind, kMaxVehicleKindBytes))
    return refused("avk.vehicle metadata 'kind'", *why);
  for (std::size_t i = 0; i < d.events.size(); ++i) {
    const std::string event = "event " + std::to_string(i) + " of the log channel:";
    if (const auto why = text_too_long(d.events[i].kind, kMaxEventKindBytes))
      return refused(event + " 'kind'", *why);
    if (const auto why = text_too_long(d.events[i].message, kMaxEventMessageBytes))
      return refused(event + " 'message'", *why);
  }
  for (std::size_t i = 0; i < d.turns.size(); ++i)
    if (const auto why = text_too_long(d.turns[i].row.reason, kMaxReasonBytes))
      return refused("turn record " + std::to_string(i) + ": 'reason'", *why);
  return Done{};
}

}  // namespace avk::app
