#include "mission/station_keeping.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::mission {

namespace {
// The least fraction of the behaviour's speed while the boat turns towards the point.
constexpr double kMinTurningSpeedFraction = 0.5;
}  // namespace

double station_keep_speed_mps(double dist_m, const StationKeepConfig& c) {
  const double inner_m = c.radius_m * c.inner_fraction;
  if (dist_m <= inner_m) return 0.0;
  // A transit slower than the hold speed never speeds up on the way in.
  const double hold = std::min(c.hold_speed_mps, c.transit_speed_mps);
  if (dist_m <= c.radius_m) return hold * (dist_m - inner_m) / (c.radius_m - inner_m);
  const double past_m = dist_m - c.radius_m;
  if (past_m >= c.slow_down_m) return c.transit_speed_mps;
  return hold + (c.transit_speed_mps - hold) * past_m / c.slow_down_m;
}

StationKeeping::StationKeeping(kinematics::Point target, StationKeepConfig config)
    : target_(target), config_(config) {}

HelmOutput StationKeeping::update(const vehicle::NavSample& s) {
  const double dx = target_.x_m - s.x_m;
  const double dy = target_.y_m - s.y_m;
  const double d = kinematics::distance_m({s.x_m, s.y_m}, target_);
  distance_m_ = d;
  if (d <= config_.radius_m) arrived_ = true;
  const double inner_m = config_.radius_m * config_.inner_fraction;
  if (d <= inner_m) {
    idle_ = true;
  } else if (d > 0.5 * (inner_m + config_.radius_m)) {
    idle_ = false;
  }
  // Idle keeps the last course: a heading towards a point a metre away swings with every
  // navigation fix, and the vehicle is not moving under it anyway.
  if (idle_) return {last_heading_deg_.value_or(s.heading_deg), 0.0};
  const double heading = kinematics::heading_of_deg(dx, dy);
  last_heading_deg_ = heading;
  // Turn before going: at full speed a boat facing away from the point would run a wide loop
  // (out of the radius) to come round. The speed is scaled by the cosine of the heading error,
  // with a floor that keeps water over the rudder.
  const double error_rad =
      kinematics::deg_to_rad(kinematics::angle180_deg(heading - s.heading_deg));
  const double turning = std::clamp(std::cos(error_rad), kMinTurningSpeedFraction, 1.0);
  return {heading, station_keep_speed_mps(d, config_) * turning};
}

}  // namespace avk::mission
