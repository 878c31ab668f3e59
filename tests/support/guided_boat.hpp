#pragma once
// A boat that holds its speed and turns at a fixed rate towards its desired heading: navigation
// logs with guidance and known arcs, for the extractor and harvester tests.

#include <algorithm>
#include <cmath>
#include <optional>

#include "kinematics/angles.hpp"
#include "vehicle/alog.hpp"

namespace avk::testing {

using vehicle::GuidedNav;

constexpr double kDt = 0.25;  // 4 Hz, as the simulated vehicles report

// Integrates a boat that holds its speed and turns at a given rate towards its desired heading.
class Boat {
 public:
  Boat(double heading_deg, double speed_mps) : heading_(heading_deg), speed_(speed_mps) {}

  // The next sample with the given guidance; yaw_rate_dps is how fast the boat turns towards the
  // desired heading (0: it keeps its course whatever is desired).
  GuidedNav step(std::optional<double> desired_heading, std::optional<double> desired_speed,
                 double yaw_rate_dps, double dt = kDt) {
    GuidedNav g;
    g.nav.t_s = t_;
    g.nav.x_m = x_;
    g.nav.y_m = y_;
    g.nav.heading_deg = avk::kinematics::wrap360_deg(heading_);
    g.nav.speed_mps = speed_;
    g.desired_heading_deg = desired_heading;
    g.desired_speed_mps = desired_speed;
    if (desired_heading && yaw_rate_dps > 0.0) {
      const double error = avk::kinematics::angle180_deg(*desired_heading - heading_);
      const double turn = std::clamp(error, -yaw_rate_dps * dt, yaw_rate_dps * dt);
      heading_ += turn;
    }
    x_ += speed_ * std::sin(avk::kinematics::deg_to_rad(heading_)) * dt;
    y_ += speed_ * std::cos(avk::kinematics::deg_to_rad(heading_)) * dt;
    t_ += dt;
    return g;
  }
  void set_heading(double h) { heading_ = h; }
  void drift(double dps) { drift_dps_ = dps; }
  void apply_drift() { heading_ += drift_dps_ * kDt; }

 private:
  double t_ = 100.0;
  double x_ = 0.0, y_ = 0.0;
  double heading_;
  double speed_;
  double drift_dps_ = 0.0;
};

}  // namespace avk::testing
