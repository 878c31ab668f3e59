#include "vehicle/nav_ranges.hpp"

#include "kinematics/number_text.hpp"

namespace avk::vehicle {

// Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "[" + std::string.
std::string to_string(const ValueRange& r) {
  std::string out = "[";
  out += kinematics::number_text(r.low);
  out += ", ";
  out += kinematics::number_text(r.high);
  out += "]";
  return out;
}

}  // namespace avk::vehicle
