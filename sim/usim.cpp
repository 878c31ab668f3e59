#include "sim/usim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::sim {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("UsimPlant: " + what);
}

// uSimMarine's slowing penalty: full rudder keeps 15 % of the speed the thrust alone would give.
constexpr double kRudderSpeedPenalty = 0.85;
// Differential drive: full forward on one side and full reverse on the other turns 36 deg/s.
constexpr double kDifferentialFullTurnDps = 36.0;

}  // namespace

UsimPlant::UsimPlant(UsimConfig c, UsimState initial) : config_(std::move(c)), state_(initial) {
  const UsimConfig& k = config_;
  require(std::isfinite(k.turn_rate) && std::isfinite(k.thrust_factor) &&
              std::isfinite(k.max_acceleration_mps2) && std::isfinite(k.max_deceleration_mps2) &&
              std::isfinite(k.rotate_speed_dps) && std::isfinite(k.drift_x_mps) &&
              std::isfinite(k.drift_y_mps),
          "configuration values must be finite");
  require(std::isfinite(initial.x_m) && std::isfinite(initial.y_m) &&
              std::isfinite(initial.heading_deg) && std::isfinite(initial.speed_mps),
          "initial state must be finite");
  if (k.thrust_map.empty()) {
    require(k.thrust_factor > 0.0, "thrust_factor must be > 0 without a thrust map");
  }
  double prev_thrust = 0.0;
  double prev_speed = 0.0;
  for (const auto& [thrust, speed] : k.thrust_map) {
    require(std::isfinite(thrust) && std::isfinite(speed), "thrust map values must be finite");
    require(thrust > prev_thrust && thrust <= 100.0,
            "thrust map thrusts must ascend within (0, 100], got " + std::to_string(thrust));
    require(speed >= prev_speed, "thrust map speeds must be >= 0 and not decrease, got " +
                                     std::to_string(speed) + " at thrust " +
                                     std::to_string(thrust));
    prev_thrust = thrust;
    prev_speed = speed;
  }
  config_.turn_rate = std::clamp(k.turn_rate, 0.0, 100.0);
  config_.max_acceleration_mps2 = std::max(0.0, k.max_acceleration_mps2);
  config_.max_deceleration_mps2 = std::max(0.0, k.max_deceleration_mps2);
  state_.heading_deg = kinematics::wrap360_deg(state_.heading_deg);
}

double UsimPlant::published_speed_mps() const {
  return std::round(state_.speed_mps * 100.0) / 100.0;
}

double UsimPlant::speed_for_thrust_mps(double thrust_pct) const {
  // uSimMarine has no reverse unless a negative map is configured; this port has none.
  if (!(thrust_pct > 0.0)) return 0.0;
  const auto& map = config_.thrust_map;
  if (map.empty()) return thrust_pct / config_.thrust_factor;
  double t0 = 0.0;
  double v0 = 0.0;
  for (const auto& [t1, v1] : map) {
    if (thrust_pct <= t1) return v0 + (v1 - v0) * (thrust_pct - t0) / (t1 - t0);
    t0 = t1;
    v0 = v1;
  }
  return map.back().second;
}

double UsimPlant::limited_target_mps(double thrust_pct, double rudder_pct, double dt_s) const {
  const double rudder_mag = std::min(std::abs(rudder_pct), 100.0);
  double target =
      speed_for_thrust_mps(thrust_pct) * (1.0 - kRudderSpeedPenalty * rudder_mag / 100.0);
  const double v = state_.speed_mps;
  const double accel = config_.max_acceleration_mps2;
  const double decel = config_.max_deceleration_mps2;
  if (target > v && accel > 0.0) target = std::min(target, v + accel * dt_s);
  if (target < v && decel > 0.0) target = std::max(target, v - decel * dt_s);
  return target;
}

void UsimPlant::step(const vehicle::ActuatorCommand& cmd, double dt_s) {
  if (!std::isfinite(dt_s) || dt_s < 0.0) {
    throw std::invalid_argument("UsimPlant::step: dt must be finite and >= 0, got " +
                                std::to_string(dt_s));
  }
  if (dt_s == 0.0) return;

  double turn_deg = 0.0;
  if (cmd.left_pct && cmd.right_pct) {
    const double left = std::clamp(*cmd.left_pct, -100.0, 100.0);
    const double right = std::clamp(*cmd.right_pct, -100.0, 100.0);
    // The difference between the sides both slows the boat (as a rudder would) and turns it, even
    // at zero speed: the thrusters push against each other.
    target_speed_mps_ = limited_target_mps((left + right) / 2.0, (left - right) / 2.0, dt_s);
    turn_deg = kDifferentialFullTurnDps * (left - right) / 200.0 * dt_s;
  } else {
    const double thrust = std::clamp(cmd.thrust_pct, -100.0, 100.0);
    target_speed_mps_ = limited_target_mps(thrust, cmd.rudder_pct, dt_s);
    // A rudder on a boat that is not moving turns nothing. The thrust factor is thrust/50: a
    // thruster-and-rudder unit turns harder the harder it pushes (0 at 0 %, 2 at 100 %).
    const double rudder =
        target_speed_mps_ == 0.0 ? 0.0 : std::clamp(cmd.rudder_pct, -100.0, 100.0);
    turn_deg = rudder * (config_.turn_rate / 100.0) * dt_s * (1.0 + (thrust - 50.0) / 50.0);
  }
  turn_deg += config_.rotate_speed_dps * dt_s;

  const double old_heading_rad = kinematics::deg_to_rad(state_.heading_deg);
  const double new_heading_deg = kinematics::wrap360_deg(state_.heading_deg + turn_deg);
  const double new_heading_rad = kinematics::deg_to_rad(new_heading_deg);
  // Trapezoidal in both speed and heading: the step moves along the mean of the old and new values.
  const double mean_speed = (state_.speed_mps + target_speed_mps_) / 2.0;
  const double course_rad = std::atan2(std::sin(old_heading_rad) + std::sin(new_heading_rad),
                                       std::cos(old_heading_rad) + std::cos(new_heading_rad));
  state_.x_m += (mean_speed * std::sin(course_rad) + config_.drift_x_mps) * dt_s;
  state_.y_m += (mean_speed * std::cos(course_rad) + config_.drift_y_mps) * dt_s;
  state_.heading_deg = new_heading_deg;
  state_.speed_mps = mean_speed;
  yaw_rate_dps_ = turn_deg / dt_s;
}

}  // namespace avk::sim
