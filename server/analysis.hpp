#pragma once
// The analyses the command line and the server both offer over the store: identification data,
// fitting and storing a yaw model, the prediction comparison and single predictions, as
// structures and as the JSON/CSV documents both serve.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/yaw_identification.hpp"
#include "store/store.hpp"

namespace avk::server {

// Resampled navigation of the missions while the helm commanded motion (or imported logs);
// segments never span missions. Throws std::runtime_error for an unknown mission or no data.
std::vector<kinematics::IdentSegment> identification_data(
    store::Store& db, const std::vector<std::int64_t>& missions,
    const kinematics::ResampleOptions& options);

struct FittedModel {
  store::StoredModel stored;  // with its id
  kinematics::IdentificationResult result;
};
FittedModel fit_and_store_model(store::Store& db, const std::string& vehicle_id,
                                const std::vector<std::int64_t>& missions,
                                const kinematics::IdentificationOptions& options,
                                const kinematics::ResampleOptions& resample = {});
nlohmann::json model_json(const store::StoredModel& m);

struct Comparison {
  std::string vehicle_id;
  std::optional<store::StoredModel> model;
  kinematics::Ckt table;
  std::vector<kinematics::CellComparison> cells;
};
// The comparison over the vehicle's ok turns (of the missions; empty: all). Throws
// std::runtime_error when there are none.
Comparison compare_from_store(store::Store& db, const std::string& vehicle_id,
                              const std::vector<std::int64_t>& missions,
                              std::optional<store::StoredModel> model,
                              double completion_threshold_deg = 5.0);
nlohmann::json comparison_json(const Comparison& c);
std::string comparison_csv(const Comparison& c);

}  // namespace avk::server
