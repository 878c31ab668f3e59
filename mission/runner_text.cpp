#include "mission/runner_text.hpp"

#include "kinematics/number_text.hpp"

namespace avk::mission {

using kinematics::fixed_text;

std::string cell_name(const TurnTask& t) {
  std::string out = fixed_text(t.speed_mps, 2);
  if (t.speed_after_mps) {
    out += " -> ";
    out += fixed_text(*t.speed_after_mps, 2);
  }
  out += " m/s, ";
  out += fixed_text(t.dheading_deg, 0);
  out += " deg";
  return out;
}

std::string position_text(const vehicle::NavSample& s) {
  std::string out = "(";
  out += fixed_text(s.x_m, 1);
  out += ", ";
  out += fixed_text(s.y_m, 1);
  out += ") m";
  return out;
}

}  // namespace avk::mission
