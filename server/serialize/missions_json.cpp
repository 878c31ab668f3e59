#include "server/serialize/missions.hpp"

#include "server/serialize/turns.hpp"
#include "server/serialize/values.hpp"
#include "server/serialize/vehicles.hpp"

namespace avk::server {

using nlohmann::json;

json mission_json(const app::MissionSummary& s) {
  const app::MissionView& m = s.mission;
  return {{"id", m.id},
          {"vehicle_id", m.vehicle_id},
          {"name", m.name},
          {"status", app::to_string(s.status)},
          {"status_reason", m.status_reason},
          {"created_utc", m.created_utc},
          {"started_s", optional_json(m.started_s)},
          {"ended_s", optional_json(m.ended_s)},
          {"started_utc", m.started_utc ? json(*m.started_utc) : json()},
          {"ended_utc", m.ended_utc ? json(*m.ended_utc) : json()},
          {"turns",
           {{"ok", s.turns.ok}, {"aborted", s.turns.aborted}, {"rejected", s.turns.rejected}}}};
}

json cells_json(const std::vector<app::CellReport>& cells) {
  json out = json::array();
  for (const auto& c : cells) {
    out.push_back({{"speed_mps", c.speed_mps},
                   {"dheading_deg", c.dheading_deg},
                   {"planned", c.planned},
                   {"ok", c.ok},
                   {"aborted", c.aborted},
                   {"rejected", c.rejected},
                   {"given_up", c.given_up},
                   {"running", c.running},
                   {"advance_m", mean_sd_json(c.advance_m)},
                   {"transfer_m", mean_sd_json(c.transfer_m)},
                   {"condition_set_time_s", mean_sd_json(c.condition_set_time_s)}});
    if (c.speed_after_mps) out.back()["speed_after_mps"] = *c.speed_after_mps;
  }
  return out;
}

json running_turn_json(const mission::RunningTurn& t) {
  return {{"t_s", t.start.t_s},
          {"x_m", t.start.x_m},
          {"y_m", t.start.y_m},
          {"heading_deg", t.start.heading_deg},
          {"speed_mps", t.speed_mps},
          {"dheading_deg", t.dheading_deg},
          {"goal_heading_deg", t.goal_heading_deg},
          {"attempt", t.attempt},
          {"speed_after_mps", optional_json(t.speed_after_mps)}};
}

json report_json(const app::MissionReport& r, bool with_config) {
  json j = mission_json(r.summary);
  j["status"] = app::status_text(r);
  j["live"] = r.live;
  j["helm_mode"] = helm_mode_json(r.helm_mode);
  j["running_turn"] = r.running_turn ? running_turn_json(*r.running_turn) : json();
  if (with_config) j["config"] = json::parse(r.summary.mission.config_json, nullptr, false);
  j["cells"] = cells_json(r.cells);
  j["duration_s"] = optional_json(r.duration_s);
  j["condition_set_time_s"] = mean_sd_json(r.condition_set_time_s);
  j["condition_set"] = {{"episodes", r.condition_set_episodes},
                        {"time_to_set_s", mean_sd_json(r.condition_set_time_s)},
                        {"turn_starts", r.condition_set_count}};
  j["turn_list"] = json::array();
  for (const auto& t : r.turns)
    j["turn_list"].push_back(turn_row_json(t));
  return j;
}

json event_json(const app::MissionEventView& e) {
  return {{"id", e.id}, {"t_s", e.t_s}, {"kind", e.kind}, {"message", e.message}};
}

json track_point_json(const app::TrackPoint& n) {
  return {{"t_s", n.t_s},
          {"x_m", n.x_m},
          {"y_m", n.y_m},
          {"heading_deg", n.heading_deg},
          {"speed_mps", n.speed_mps},
          {"desired_heading_deg", optional_json(n.desired_heading_deg)},
          {"desired_speed_mps", optional_json(n.desired_speed_mps)},
          {"helm_mode", n.helm_mode}};
}

json missions_json(const std::vector<app::MissionSummary>& missions) {
  json out = json::array();
  for (const auto& m : missions)
    out.push_back(mission_json(m));
  return out;
}

json events_page_json(const app::Page<app::MissionEventView>& page) {
  return page_json(page, [](const app::MissionEventView& e) { return event_json(e); });
}

json nav_page_json(const app::Page<app::TrackPoint>& page) {
  return page_json(page, [](const app::TrackPoint& row) { return track_point_json(row); });
}

json turn_started_json(const mission::RunningTurn& t, std::int64_t mission_id) {
  json j = running_turn_json(t);
  j["event"] = "started";
  j["mission_id"] = mission_id;
  return j;
}

json turn_ended_json(const mission::TurnOutcome& t, std::int64_t mission_id) {
  json j = {{"event",
             t.status == kinematics::TurnStatus::ok ? "finished" : kinematics::to_string(t.status)},
            {"mission_id", mission_id},
            {"status", kinematics::to_string(t.status)},
            {"reason", t.reason},
            {"speed_mps", t.task.speed_mps},
            {"goal_dheading_deg", t.raw.meta().goal_dheading_deg},
            {"requeued", t.requeued},
            {"given_up", t.given_up}};
  j["id"] = t.stored_id ? json(*t.stored_id) : json();
  j["advance_m"] = t.advance_m ? json(*t.advance_m) : json();
  j["transfer_m"] = t.transfer_m ? json(*t.transfer_m) : json();
  j["condition_set_time_s"] = t.condition_set_time_s ? json(*t.condition_set_time_s) : json();
  return j;
}

json mission_progress_json(std::int64_t mission_id, const std::string& state,
                           mission::HelmMode helm_mode, const std::vector<app::CellReport>& cells) {
  return {{"mission_id", mission_id},
          {"state", state},
          {"helm_mode", mission::to_string(helm_mode)},
          {"cells", cells_json(cells)}};
}

}  // namespace avk::server
