#pragma once
// MOOS-IvP's uSimMarine (2015 release) kinematics, reimplemented: the simulator the thesis
// collected its simulated turns with. Not a physical model: speed follows thrust through a table
// with a rudder penalty and acceleration limits, heading turns at a rate proportional to rudder and
// thrust. Kept as it was so simulated turns compare with the thesis.

#include <utility>
#include <vector>

#include "vehicle/vehicle.hpp"

namespace avk::sim {

struct UsimConfig {
  double turn_rate = 70.0;  // clamped to [0, 100]; the thesis used 30
  double thrust_factor = 20.0;
  // Optional (thrust %, speed m/s) pairs, piecewise linear through (0,0), flat after the last pair;
  // replaces thrust/thrust_factor when not empty. Thrusts in (0, 100] ascending, speeds >= 0 and
  // not decreasing (uSimMarine rejects other maps too).
  std::vector<std::pair<double, double>> thrust_map;
  double max_acceleration_mps2 = 0.0;  // 0 = no limit
  double max_deceleration_mps2 = 0.5;  // 0 = no limit
  double rotate_speed_dps = 0.0;
  double drift_x_mps = 0.0;
  double drift_y_mps = 0.0;
};

// Heading degrees in [0, 360) clockwise from north; x east, y north; speed through the water.
struct UsimState {
  double x_m = 0, y_m = 0, heading_deg = 0, speed_mps = 0;
};

class UsimPlant {
 public:
  // Throws std::invalid_argument for a non-finite value, a thrust factor <= 0 without a thrust
  // map, or a thrust map that breaks the rules above. Negative acceleration limits become 0.
  UsimPlant(UsimConfig c, UsimState initial);

  // Advances dt_s seconds holding cmd. Differential mode when cmd.left_pct and cmd.right_pct are
  // both set, rudder/thrust otherwise; every percentage is clamped to ±100. dt_s == 0 does nothing;
  // a negative or non-finite dt_s throws std::invalid_argument.
  //
  // The stored speed after a step is the mean of the old speed and the new speed target, the speed
  // the position was advanced with: uSimMarine's SimEngine::propagate writes that speed back into
  // its record, so the speed lags thrust by one more half step than the target alone would. With
  // the raw target stored instead, the thesis turn sags to 0.67 m/s rather than its 0.70.
  void step(const vehicle::ActuatorCommand& cmd, double dt_s);

  const UsimState& state() const { return state_; }
  const UsimConfig& config() const { return config_; }
  // Rounded to 0.01 m/s as uSimMarine publishes NAV_SPEED.
  double published_speed_mps() const;
  // Heading change of the last step over its duration (deg/s, + to starboard); 0 before any step.
  double yaw_rate_dps() const { return yaw_rate_dps_; }
  // The speed target of the last step (thrust table, rudder penalty, acceleration limits).
  double target_speed_mps() const { return target_speed_mps_; }

  // Speed for a thrust through the thrust map or thrust factor, before the rudder penalty.
  double speed_for_thrust_mps(double thrust_pct) const;

 private:
  double limited_target_mps(double thrust_pct, double rudder_pct, double dt_s) const;

  UsimConfig config_;
  UsimState state_;
  double yaw_rate_dps_ = 0.0;
  double target_speed_mps_ = 0.0;
};

}  // namespace avk::sim
