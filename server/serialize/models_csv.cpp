#include "server/serialize/models.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

std::string models_csv(const std::vector<app::ModelView>& models) {
  std::string csv =
      "id,created_utc,vehicle_id,form,history_samples,rate_hz,ridge_lambda,refined,"
      "training_missions,train_one_step_rms_deg,validation_mse_m2,validation_heading_rms_deg,"
      "speed_gain,speed_sag_per_deg,speed_bias_mps\n";
  for (const auto& m : models) {
    // The training missions in one cell, space-separated: a list is not a CSV column.
    std::string missions;
    for (const auto id : m.training_missions) {
      if (!missions.empty()) missions += ' ';
      missions += std::to_string(id);
    }
    const auto& y = m.model;
    csv += std::to_string(m.id) + ',' + csv_cell(m.created_utc) + ',' + csv_cell(m.vehicle_id) +
           ',' + kin::to_string(y.form) + ',' + std::to_string(y.history) + ',' + num(y.rate_hz) +
           ',' + num(y.ridge_lambda) + ',' + (y.refined ? "true" : "false") + ',' + missions + ',' +
           optional_csv(m.train_one_step_rms_deg) + ',' + optional_csv(m.validation_mse_m2) + ',' +
           optional_csv(m.validation_heading_rms_deg) + ',' +
           (y.speed ? num(y.speed->gain) + ',' + num(y.speed->sag_per_deg) + ',' +
                          num(y.speed->bias_mps)
                    : std::string(",,")) +
           '\n';
  }
  return csv;
}

std::string sweep_csv(const std::vector<kin::HistorySweepRow>& rows) {
  std::string csv =
      "history_s,history_samples,train_one_step_rms_deg,validation_mse_m2,"
      "validation_heading_rms_deg,validation_turns\n";
  for (const auto& r : rows)
    csv += num(r.history_s) + ',' + std::to_string(r.history) + ',' +
           num(r.train_one_step_rms_deg) + ',' + num(r.validation.position_mse_m2) + ',' +
           num(r.validation.heading_rms_deg) + ',' + std::to_string(r.validation.windows) + '\n';
  return csv;
}

}  // namespace avk::server
