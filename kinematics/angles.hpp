#pragma once
// Angle conventions used everywhere (MOOS): heading in degrees clockwise from north (+y), local
// grid x = east, y = north. Functions say in their names which unit they take and give.

#include <cmath>
#include <numbers>
#include <vector>

namespace avk::kinematics {

constexpr double deg_to_rad(double deg) {
  return deg * std::numbers::pi / 180.0;
}
constexpr double rad_to_deg(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

// Heading in [0, 360).
inline double wrap360_deg(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  return r >= 360.0 ? 0.0 : r;
}

// Signed angle in (-180, 180]: the MOOS angle180 used for heading errors.
inline double angle180_deg(double deg) {
  double r = wrap360_deg(deg);
  return r > 180.0 ? r - 360.0 : r;
}

// Heading (deg, clockwise from north) of the direction (dx east, dy north).
inline double heading_of_deg(double dx_east, double dy_north) {
  return wrap360_deg(rad_to_deg(std::atan2(dx_east, dy_north)));
}

// Removes 360-degree jumps so consecutive values differ by at most 180 degrees; the first value is
// kept as it is. Needed before differencing or interpolating headings (350 -> 10 is +20, not -340).
inline std::vector<double> unwrap_deg(const std::vector<double>& headings_deg) {
  std::vector<double> out;
  out.reserve(headings_deg.size());
  for (double h : headings_deg) {
    if (out.empty()) {
      out.push_back(h);
    } else {
      out.push_back(out.back() + angle180_deg(h - out.back()));
    }
  }
  return out;
}

}  // namespace avk::kinematics
