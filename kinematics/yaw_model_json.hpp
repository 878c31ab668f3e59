#pragma once
// The yaw model as a JSON document (stored with each identified model, and what `avk model`
// prints): form, history, rate, coefficients, ridge strength, refinement, speed model.

#include <string>
#include <string_view>

#include "kinematics/yaw_model.hpp"

namespace avk::kinematics {

std::string yaw_model_to_json(const YawModel& m);
// Throws ParseError (kinematics/parse_error.hpp) naming the JSON pointer of a bad field.
YawModel parse_yaw_model_json(std::string_view text);

}  // namespace avk::kinematics
