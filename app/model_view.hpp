#pragma once
// An identified black-box yaw model with what it was trained on and how well it validated (the
// front ends' type, not the store's row: app/mission_views.hpp).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/yaw_model.hpp"

namespace avk::app {

struct ModelView {
  std::int64_t id = 0;
  std::string created_utc;  // ISO 8601
  std::string vehicle_id;
  std::vector<std::int64_t> training_missions;
  kinematics::YawModel model;
  std::optional<double> train_one_step_rms_deg;
  std::optional<double> validation_mse_m2;  // trajectory position MSE on validation turns
  std::optional<double> validation_heading_rms_deg;
};

}  // namespace avk::app
