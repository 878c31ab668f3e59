#include "server/serialize/turns.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

std::string turns_csv(const std::vector<app::TurnView>& rows) {
  std::string csv =
      "id,mission_id,vehicle_id,status,reason,speed_mps,goal_dheading_deg,"
      "observed_dheading_deg,start_time_s,end_time_s,advance_m,transfer_m,"
      "condition_set_time_s,start_heading_error_deg,start_yaw_rate_dps\n";
  for (const auto& t : rows)
    csv += std::to_string(t.id) + ',' + std::to_string(t.mission_id) + ',' +
           csv_cell(t.vehicle_id) + ',' + kin::to_string(t.status) + ',' + csv_cell(t.reason) +
           ',' + num(t.commanded_speed_mps) + ',' + num(t.goal_dheading_deg) + ',' +
           num(t.observed_dheading_deg) + ',' + num(t.start_time_s) + ',' + num(t.end_time_s) +
           ',' + optional_csv(t.advance_m) + ',' + optional_csv(t.transfer_m) + ',' +
           optional_csv(t.condition_set_time_s) + ',' + optional_csv(t.start_heading_error_deg) +
           ',' + optional_csv(t.start_yaw_rate_dps) + '\n';
  return csv;
}

}  // namespace avk::server
