#pragma once
// Numbers in the station's text outputs (CSV cells, messages): the shortest text that reads back
// as the same double, as JSON writes it.

#include <nlohmann/json.hpp>
#include <string>

namespace avk::server {

inline std::string num(double v) {
  return nlohmann::json(v).dump();
}

}  // namespace avk::server
