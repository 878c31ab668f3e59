#include "server/serialize/missions.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

std::string missions_csv(const std::vector<app::MissionSummary>& missions) {
  std::string csv =
      "id,vehicle_id,name,status,created_utc,started_s,ended_s,started_utc,ended_utc,turns_ok,"
      "turns_aborted,turns_rejected\n";
  for (const auto& s : missions) {
    const auto& m = s.mission;
    csv += std::to_string(m.id) + ',' + csv_cell(m.vehicle_id) + ',' + csv_cell(m.name) + ',' +
           app::to_string(s.status) + ',' + csv_cell(m.created_utc) + ',' +
           optional_csv(m.started_s) + ',' + optional_csv(m.ended_s) + ',' +
           csv_cell(m.started_utc.value_or("")) + ',' + csv_cell(m.ended_utc.value_or("")) + ',' +
           std::to_string(s.turns.ok) + ',' + std::to_string(s.turns.aborted) + ',' +
           std::to_string(s.turns.rejected) + '\n';
  }
  return csv;
}

std::string events_csv(const std::vector<app::MissionEventView>& events) {
  std::string csv = "id,t_s,kind,message\n";
  for (const auto& e : events)
    csv += std::to_string(e.id) + ',' + num(e.t_s) + ',' + csv_cell(e.kind) + ',' +
           csv_cell(e.message) + '\n';
  return csv;
}

std::string nav_csv(const std::vector<app::TrackPoint>& rows) {
  std::string csv =
      "t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,helm_mode\n";
  for (const auto& r : rows) {
    const app::TrackPoint& n = r;
    csv += num(n.t_s) + ',' + num(n.x_m) + ',' + num(n.y_m) + ',' + num(n.heading_deg) + ',' +
           num(n.speed_mps) + ',' + optional_csv(n.desired_heading_deg) + ',' +
           optional_csv(n.desired_speed_mps) + ',' + csv_cell(n.helm_mode) + '\n';
  }
  return csv;
}

std::string report_cells_csv(const app::MissionReport& r) {
  std::string csv =
      "speed_mps,dheading_deg,planned,ok,aborted,rejected,advance_mean_m,advance_sd_m,"
      "transfer_mean_m,transfer_sd_m,condition_set_mean_s,condition_set_sd_s\n";
  for (const auto& c : r.cells)
    csv += num(c.speed_mps) + ',' + num(c.dheading_deg) + ',' + std::to_string(c.planned) + ',' +
           std::to_string(c.ok) + ',' + std::to_string(c.aborted) + ',' +
           std::to_string(c.rejected) + ',' + mean_csv(c.advance_m) + ',' + sd_csv(c.advance_m) +
           ',' + mean_csv(c.transfer_m) + ',' + sd_csv(c.transfer_m) + ',' +
           mean_csv(c.condition_set_time_s) + ',' + sd_csv(c.condition_set_time_s) + '\n';
  return csv;
}

}  // namespace avk::server
