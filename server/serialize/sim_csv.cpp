#include "server/serialize/sim.hpp"

#include "server/serialize/values.hpp"

namespace avk::server {

std::string sim_turn_csv(const sim::TurnScenarioResult& r) {
  std::string csv =
      "t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,rudder_pct,"
      "thrust_pct\n";
  for (const auto& row : r.rows)
    csv += num(row.t_s) + ',' + num(row.x_m) + ',' + num(row.y_m) + ',' + num(row.heading_deg) +
           ',' + num(row.speed_mps) + ',' + num(row.desired_heading_deg) + ',' +
           num(row.desired_speed_mps) + ',' + num(row.rudder_pct) + ',' + num(row.thrust_pct) +
           '\n';
  return csv;
}

std::string variability_csv(const sim::VariabilityResult& v) {
  std::string csv = "repetition,seed,completed,advance_m,transfer_m\n";
  for (const auto& row : v.rows)
    csv += std::to_string(row.repetition) + ',' + std::to_string(row.seed) + ',' +
           (row.completed ? '1' : '0') + ',' + num(row.advance_m) + ',' + num(row.transfer_m) +
           '\n';
  return csv + "# advance " + num(v.advance_m.mean) + " +- " + num(v.advance_m.sd) + " m (CV " +
         num(v.advance_cv) + "), transfer " + num(v.transfer_m.mean) + " +- " +
         num(v.transfer_m.sd) + " m (CV " + num(v.transfer_cv) + "), " +
         std::to_string(v.distinct_outcomes) + " distinct outcomes at 1 cm\n";
}

std::string tick_sweep_csv(const std::vector<TickSweepRow>& rows) {
  std::string csv =
      "tick_hz,repeats,advance_mean_m,advance_sd_m,advance_cv,transfer_mean_m,transfer_sd_m,"
      "transfer_cv,distinct_outcomes\n";
  for (const auto& r : rows) {
    const sim::VariabilityResult& v = r.result;
    csv += std::to_string(r.tick_hz) + ',' + std::to_string(r.repeats) + ',' +
           num(v.advance_m.mean) + ',' + num(v.advance_m.sd) + ',' + num(v.advance_cv) + ',' +
           num(v.transfer_m.mean) + ',' + num(v.transfer_m.sd) + ',' + num(v.transfer_cv) + ',' +
           std::to_string(v.distinct_outcomes) + '\n';
  }
  return csv;
}

}  // namespace avk::server
