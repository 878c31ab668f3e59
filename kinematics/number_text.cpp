#include "kinematics/number_text.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace avk::kinematics {

std::string number_text(double v) {
  return nlohmann::json(v).dump();
}

std::string fixed_text(double v, int decimals) {
  char buf[352];  // the widest finite double with up to 20 decimals fits
  std::snprintf(buf, sizeof buf, "%.*f", decimals < 0 ? 0 : decimals > 20 ? 20 : decimals, v);
  return buf;
}

}  // namespace avk::kinematics
