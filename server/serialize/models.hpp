#pragma once
// Identified yaw models as documents: a model, the listing, its headings over a mission, the
// sweep over history length.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/models.hpp"
#include "kinematics/yaw_identification.hpp"

namespace avk::server {

// with_coefficients: the full model document; without, the listing's summary.
nlohmann::json model_json(const app::ModelView& m, bool with_coefficients = true);
// The listing: model_json of each without its coefficients.
nlohmann::json models_json(const std::vector<app::ModelView>& models);
// The listing's summary (no coefficients), the speed model as speed_gain, ...
std::string models_csv(const std::vector<app::ModelView>& models);
nlohmann::json model_headings_json(const app::ModelHeadings& h);
nlohmann::json sweep_json(const std::vector<kinematics::HistorySweepRow>& rows);
std::string sweep_csv(const std::vector<kinematics::HistorySweepRow>& rows);

}  // namespace avk::server
