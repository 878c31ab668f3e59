#include "server/serialize/turns.hpp"

#include "kinematics/turn_json.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

json turn_row_json(const app::TurnView& t) {
  return {{"id", t.id},
          {"mission_id", t.mission_id},
          {"vehicle_id", t.vehicle_id},
          {"status", kin::to_string(t.status)},
          {"reason", t.reason},
          {"speed_mps", t.commanded_speed_mps},
          {"goal_dheading_deg", t.goal_dheading_deg},
          {"observed_dheading_deg", t.observed_dheading_deg},
          {"start_time_s", t.start_time_s},
          {"end_time_s", t.end_time_s},
          {"advance_m", optional_json(t.advance_m)},
          {"transfer_m", optional_json(t.transfer_m)},
          {"condition_set_time_s", optional_json(t.condition_set_time_s)},
          {"start_heading_error_deg", optional_json(t.start_heading_error_deg)},
          {"start_yaw_rate_dps", optional_json(t.start_yaw_rate_dps)},
          {"source", kin::to_string(t.source)},
          {"quality", optional_json(t.quality)},
          {"speed_after_mps", optional_json(t.speed_after_mps)}};
}

json harvest_report_json(const app::HarvestReport& r) {
  return {{"mission_id", r.mission_id},
          {"vehicle_id", r.vehicle_id},
          {"harvest_id", r.harvest_id},
          {"nav_rows", r.nav_rows},
          {"steps", r.steps},
          {"harvested", r.harvested},
          {"already_recorded", r.already_recorded},
          {"rejected", r.rejected},
          {"rejected_by_reason", r.rejected_by_reason},
          {"turn_ids", r.turn_ids},
          {"mean_quality", r.harvested > 0 ? json(r.mean_quality) : json()}};
}

json turn_json(const app::TurnDetail& t) {
  json j = turn_row_json(t.row);
  j["raw"] = json::parse(kin::to_json_string(t.raw));
  j["normalized"] = t.normalized ? json::parse(kin::to_json_string(*t.normalized)) : json();
  return j;
}

json harvest_reports_json(const std::vector<app::HarvestReport>& reports) {
  json missions = json::array();
  for (const auto& r : reports)
    missions.push_back(harvest_report_json(r));
  return {{"missions", std::move(missions)}};
}

json turns_page_json(const app::Page<app::TurnView>& page) {
  return page_json(page, [](const app::TurnView& t) { return turn_row_json(t); });
}

}  // namespace avk::server
