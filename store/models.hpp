#pragma once
// Identified black-box yaw models, with what they were trained on and how well they validated.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/yaw_model.hpp"
#include "store/store_error.hpp"

namespace avk::store {

// An identified black-box yaw model with its provenance and validation errors.
struct StoredModel {
  std::int64_t id = 0;
  std::string created_utc;
  std::string vehicle_id;
  std::vector<std::int64_t> training_missions;
  kinematics::YawModel model;
  std::optional<double> train_one_step_rms_deg;
  std::optional<double> validation_mse_m2;  // trajectory position MSE on validation turns
  std::optional<double> validation_heading_rms_deg;
};

class ModelRepository {
 public:
  virtual ~ModelRepository() = default;

  // Returns the model id (m.id is ignored). Reads throw StoreError for a corrupt document.
  virtual std::int64_t save(const StoredModel& m) = 0;
  virtual std::optional<StoredModel> get(std::int64_t id) = 0;
  // Oldest first; every vehicle's without vehicle_id.
  virtual std::vector<StoredModel> list(const std::optional<std::string>& vehicle_id = {}) = 0;
  virtual std::optional<StoredModel> latest(const std::optional<std::string>& vehicle_id = {}) = 0;
};

}  // namespace avk::store
