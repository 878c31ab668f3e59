#include "vehicle/marine_pid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::vehicle {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

ScalarPid::ScalarPid(PidGains g) : gains_(g) {
  require(std::isfinite(g.kp) && std::isfinite(g.kd) && std::isfinite(g.ki) &&
              std::isfinite(g.integral_limit),
          "PID gains and integral limit must be finite");
}

double ScalarPid::run(double error, double t_s) {
  double dt = 0.0;
  if (started_) {
    dt = t_s - prev_t_s_;
    if (dt < 0.0) {
      throw std::invalid_argument("ScalarPid::run: time went backwards by " + std::to_string(-dt) +
                                  " s");
    }
    // Two errors at one instant carry no rate information; keep the last answer.
    if (dt == 0.0) return output_;
    slopes_.push_front((error - prev_error_) / dt);
    if (slopes_.size() > kDerivativeWindow) slopes_.pop_back();
    derivative_ =
        std::accumulate(slopes_.begin(), slopes_.end(), 0.0) / static_cast<double>(slopes_.size());
  } else {
    derivative_ = 0.0;
  }

  if (gains_.ki > 0.0) {
    const double lim = std::abs(gains_.integral_limit);
    integral_ = std::clamp(integral_ + gains_.ki * error * dt, -lim, lim);
  } else {
    integral_ = 0.0;
  }

  output_ = std::clamp(gains_.kp * error + gains_.kd * derivative_ + integral_, -kOutputLimit,
                       kOutputLimit);
  started_ = true;
  prev_error_ = error;
  prev_t_s_ = t_s;
  return output_;
}

void ScalarPid::reset() {
  started_ = false;
  prev_error_ = 0.0;
  prev_t_s_ = 0.0;
  integral_ = 0.0;
  derivative_ = 0.0;
  output_ = 0.0;
  slopes_.clear();
}

MarinePidConfig MarinePidConfig::thesis_sim() {
  return MarinePidConfig{};
}

MarinePidConfig MarinePidConfig::m200_in_water() {
  MarinePidConfig c;
  c.yaw = PidGains{0.5, 0.0, 0.0, 20.0};
  c.speed = PidGains{1.0, 0.0, 0.0, 0.0};
  return c;
}

MarinePid::MarinePid(MarinePidConfig c) : config_(c), yaw_pid_(c.yaw), speed_pid_(c.speed) {
  require(std::isfinite(c.max_rudder_pct) && c.max_rudder_pct >= 0.0,
          "max_rudder_pct must be finite and >= 0");
  require(std::isfinite(c.max_thrust_pct) && c.max_thrust_pct >= 0.0,
          "max_thrust_pct must be finite and >= 0");
  require(std::isfinite(c.speed_factor), "speed_factor must be finite");
  require(std::isfinite(c.tardy_s) && c.tardy_s >= 0.0, "tardy_s must be finite and >= 0");
}

void MarinePid::reset() {
  yaw_pid_.reset();
  speed_pid_.reset();
  thrust_memory_pct_ = 0.0;
  paused_ = false;
}

ActuatorCommand MarinePid::step(double now_s, const std::optional<NavSample>& nav,
                                const std::optional<DesiredCommand>& desired) {
  const bool tardy = !nav || !desired || now_s - nav->t_s > config_.tardy_s ||
                     now_s - desired->t_s > config_.tardy_s;
  if (tardy) {
    reset();
    paused_ = true;
    return ActuatorCommand{};
  }
  paused_ = false;

  // Heading error in (-180, 180]; a positive error (heading right of desired) needs port rudder.
  const double heading_error_deg =
      kinematics::angle180_deg(nav->heading_deg - kinematics::angle180_deg(desired->heading_deg));
  double rudder_pct = std::clamp(-yaw_pid_.run(heading_error_deg, now_s), -config_.max_rudder_pct,
                                 config_.max_rudder_pct);

  double thrust_pct = 0.0;
  if (config_.speed_factor != 0.0) {
    thrust_pct = desired->speed_mps * config_.speed_factor;
  } else {
    // Incremental: the PID output is a thrust change, so steady state needs no integral term.
    thrust_pct = thrust_memory_pct_ + speed_pid_.run(desired->speed_mps - nav->speed_mps, now_s);
  }
  // No reverse: the simulator and the M200 mixing treat negative thrust as "stop" anyway.
  if (thrust_pct < 0.0) thrust_pct = 0.0;
  thrust_pct = std::clamp(thrust_pct, -config_.max_thrust_pct, config_.max_thrust_pct);
  if (std::abs(desired->speed_mps) <= 0.001) thrust_pct = 0.0;
  // A rudder without thrust only wastes the actuator (and spins a differential drive in place).
  if (thrust_pct == 0.0) rudder_pct = 0.0;

  thrust_memory_pct_ = thrust_pct;
  return ActuatorCommand{rudder_pct, thrust_pct, std::nullopt, std::nullopt};
}

}  // namespace avk::vehicle
