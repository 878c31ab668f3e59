#pragma once
// The fields (JSON pointers) the validation of a mutated copy of the Figure 4-1 mission names.

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mission/mission_config.hpp"
#include "support/example_file.hpp"

namespace avk::testing {

inline std::vector<std::string> mission_field_errors(
    const std::function<void(nlohmann::json&)>& mutate, double vmax = 2.0) {
  nlohmann::json doc = nlohmann::json::parse(example_text("thesis-fig4-1.json"));
  mutate(doc);
  try {
    mission::parse_mission_config(doc.dump(), vmax);
  } catch (const mission::MissionConfigError& e) {
    std::vector<std::string> f;
    for (const auto& err : e.errors())
      f.push_back(err.field);
    return f;
  }
  return {};
}

}  // namespace avk::testing
