#include "vehicle/thrust_mixing.hpp"

#include <algorithm>
#include <cmath>

namespace avk::vehicle {

namespace {

// Moves what `side` has beyond ±limit off `other`.
void spill(double side, double& other, double limit) {
  if (side > limit) {
    other -= side - limit;
  } else if (side < -limit) {
    other -= side + limit;
  }
}

}  // namespace

DifferentialThrust mix_differential(double rudder_pct, double thrust_pct, const MixConfig& c) {
  const double rudder_limit = std::abs(c.max_rudder_mix_pct);
  const double limit = std::abs(c.max_thrust_pct);
  const double rud = std::clamp(rudder_pct, -rudder_limit, rudder_limit);
  const double thr = std::clamp(thrust_pct, -100.0, 100.0);
  const double scale = limit / 100.0;
  double left = (thr + rud) * scale;
  double right = (thr - rud) * scale;
  spill(left, right, limit);
  spill(right, left, limit);
  return DifferentialThrust{std::clamp(left, -limit, limit), std::clamp(right, -limit, limit)};
}

}  // namespace avk::vehicle
