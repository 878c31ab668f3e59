#pragma once
// What tests send a running station: the headers of a control request, and a small collection
// mission (two speeds by two heading changes in a 200 m square) to start over REST.

#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace avk::testing {

inline std::map<std::string, std::string> control_headers(const std::string& token) {
  return {{"Authorization", "Bearer " + token}, {"Content-Type", "application/json"}};
}

inline std::string small_mission(const std::string& name, int repeats = 1) {
  using nlohmann::json;
  return json{{"name", name},
              {"turn_array",
               {{"speeds_mps", {0.5, 1.0}}, {"dheadings_deg", {40, 100}}, {"repeats", repeats}}},
              {"operating_region",
               {{"polygon_m", {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}},
                {"buffer_m", 25},
                {"return_point_m", {0, -70}}}}}
      .dump();
}

}  // namespace avk::testing
