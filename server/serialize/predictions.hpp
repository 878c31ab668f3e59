#pragma once
// A prediction as a document: the trajectory with what it was predicted from and against.

#include <nlohmann/json.hpp>
#include <string>

#include "app/predict.hpp"
#include "kinematics/geometry.hpp"

namespace avk::server {

nlohmann::json prediction_json(const app::Prediction& p);
std::string trajectory_csv(const kinematics::Polyline& line);

}  // namespace avk::server
