#include "server/serialize/vehicles.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

std::string vehicles_csv(const std::vector<app::VehicleStatus>& vehicles) {
  std::string csv =
      "id,kind,max_speed_mps,link,helm_mode,desired_heading_deg,desired_speed_mps,mission_id,"
      "t_s,nav_t_s,x_m,y_m,heading_deg,speed_mps\n";
  for (const auto& v : vehicles) {
    csv += csv_cell(v.info.id) + ',' + csv_cell(v.info.kind) + ',' +
           (v.info.max_speed_mps > 0.0 ? num(v.info.max_speed_mps) : std::string()) + ',';
    if (!v.live) {
      csv += vehicle::to_string(vehicle::LinkState::disconnected);
      csv += ",,,,,,,,,,\n";
      continue;
    }
    const app::VehicleSnapshot& l = *v.live;
    csv += std::string(vehicle::to_string(l.link)) + ',' +
           (l.helm_mode ? std::string(mission::to_string(*l.helm_mode)) : std::string()) + ',' +
           optional_csv(l.desired_heading_deg) + ',' + optional_csv(l.desired_speed_mps) + ',' +
           (l.mission_id ? std::to_string(*l.mission_id) : std::string()) + ',' + num(l.t_s);
    if (l.nav)
      csv += ',' + num(l.nav->t_s) + ',' + num(l.nav->x_m) + ',' + num(l.nav->y_m) + ',' +
             num(l.nav->heading_deg) + ',' + num(l.nav->speed_mps) + '\n';
    else
      csv += ",,,,,\n";
  }
  return csv;
}

}  // namespace avk::server
