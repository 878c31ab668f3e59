#pragma once
// Station keeping in the manner of MOOS' BHV_StationKeep: a closed loop on position, so it holds
// against current and wind without knowing them. Far from the point the vehicle transits at the
// transit speed; approaching, it slows down; inside the outer radius the speed is proportional to
// the distance past the inner radius (capped at the hold speed); inside the inner radius it idles
// (speed 0, drifting) until it drifts halfway out to the outer radius. The hysteresis keeps a
// boat that is on station from hunting around the point on every GNSS jitter; steering again
// halfway, not at the outer radius, leaves the band's other half for the turn back, so a boat
// idling in a current stays inside the outer radius.
//
// Also the go-to (transit to a point, then hold) and all stop behaviours the station's vehicle
// commands use. Pure helm logic: navigation in, desired heading and speed out.

#include <optional>

#include "kinematics/geometry.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

// The default hold radius and its limits (the station's commands validate against these).
inline constexpr double kDefaultHoldRadiusM = 5.0;
inline constexpr double kMaxHoldRadiusM = 500.0;

struct StationKeepConfig {
  double radius_m = kDefaultHoldRadiusM;  // the outer radius: past it the vehicle steers back
  double inner_fraction = 0.2;            // idle inside radius_m x this
  double hold_speed_mps = 1.0;            // the speed at the outer radius
  double transit_speed_mps = 1.5;         // far from the point
  // Beyond radius_m + this the vehicle transits at transit_speed_mps; nearer, the speed falls
  // linearly to hold_speed_mps at the outer radius, so it does not overshoot the point.
  double slow_down_m = 30.0;
};

struct HelmOutput {
  double heading_deg = 0.0;
  double speed_mps = 0.0;
};

// The speed for a vehicle dist_m from the point while it is steering (not idle): transit far out,
// a linear slow-down to the hold speed at the outer radius, proportional inside it.
double station_keep_speed_mps(double dist_m, const StationKeepConfig& c);

class StationKeeping {
 public:
  StationKeeping(kinematics::Point target, StationKeepConfig config);

  // One helm step on the newest navigation.
  HelmOutput update(const vehicle::NavSample& s);

  kinematics::Point target() const { return target_; }
  const StationKeepConfig& config() const { return config_; }
  // Once within the outer radius: from then on the vehicle is on station (holding).
  bool arrived() const { return arrived_; }
  bool idle() const { return idle_; }
  std::optional<double> distance_m() const { return distance_m_; }

 private:
  kinematics::Point target_;
  StationKeepConfig config_;
  bool arrived_ = false;
  bool idle_ = false;
  std::optional<double> distance_m_;
  std::optional<double> last_heading_deg_;
};

}  // namespace avk::mission
