#pragma once
// The comparison of the prediction methods as documents: leave-one-out first, the thesis'
// in-sample table, held-out test missions and speed changes.

#include <nlohmann/json.hpp>
#include <string>

#include "app/compare.hpp"

namespace avk::server {

nlohmann::json comparison_json(const app::Comparison& c);
// The thesis' in-sample table.
std::string comparison_csv(const app::Comparison& c);
// The leave-one-out table: path distance and y(x) MSE of every method, and corridor coverage.
std::string predictive_csv(const app::Comparison& c);

}  // namespace avk::server
