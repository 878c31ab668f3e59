#pragma once
// What every curve fit checks of the points it is given before fitting them.

#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/geometry.hpp"

namespace avk::kinematics {

// Throws std::invalid_argument, naming the fit (`who`) and the point, for a coordinate that is
// not finite: one NaN would spread through the whole least-squares solution.
inline void require_finite(const Polyline& points, const char* who) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x_m) || !std::isfinite(points[i].y_m))
      throw std::invalid_argument(std::string(who) + ": non-finite coordinate at point " +
                                  std::to_string(i));
  }
}

}  // namespace avk::kinematics
