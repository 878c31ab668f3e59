#include "server/serialize/models.hpp"

#include "kinematics/yaw_model_json.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

json model_json(const app::ModelView& m, bool with_coefficients) {
  json j = json::parse(kin::yaw_model_to_json(m.model));
  j["id"] = m.id;
  j["created_utc"] = m.created_utc;
  j["vehicle_id"] = m.vehicle_id;
  j["training_missions"] = m.training_missions;
  j["train_one_step_rms_deg"] = optional_json(m.train_one_step_rms_deg);
  j["validation_mse_m2"] = optional_json(m.validation_mse_m2);
  j["validation_heading_rms_deg"] = optional_json(m.validation_heading_rms_deg);
  if (!with_coefficients) {
    j.erase("error_coeffs");
    j.erase("heading_coeffs");
  }
  return j;
}

json model_headings_json(const app::ModelHeadings& h) {
  const auto optional_array = [](const std::vector<std::optional<double>>& v) {
    json a = json::array();
    for (const auto& x : v)
      a.push_back(optional_json(x));
    return a;
  };
  json segments = json::array();
  for (const auto& s : h.segments)
    segments.push_back({{"t0_s", s.t0_s},
                        {"heading_deg", s.heading_deg},
                        {"desired_heading_deg", s.desired_heading_deg},
                        {"one_step_deg", optional_array(s.one_step_deg)},
                        {"simulated_deg", optional_array(s.simulated_deg)}});
  return {{"model_id", h.model_id},
          {"mission_id", h.mission_id},
          {"dt_s", h.dt_s},
          {"warmup_samples", h.warmup},
          {"restart_step_deg", h.restart_step_deg},
          {"segments", segments}};
}

json sweep_json(const std::vector<kin::HistorySweepRow>& rows) {
  json out = json::array();
  for (const auto& row : rows)
    out.push_back({{"history_s", row.history_s},
                   {"history_samples", row.history},
                   {"train_one_step_rms_deg", row.train_one_step_rms_deg},
                   {"validation_mse_m2", row.validation.position_mse_m2},
                   {"validation_heading_rms_deg", row.validation.heading_rms_deg},
                   {"validation_turns", row.validation.windows}});
  return out;
}

json models_json(const std::vector<app::ModelView>& models) {
  json out = json::array();
  for (const auto& m : models)
    out.push_back(model_json(m, false));
  return out;
}

}  // namespace avk::server
