#pragma once
// The backseat controller below the helm: MOOS-IvP's pMarinePID (2015 release), reimplemented.
// Desired heading and speed in, rudder and thrust percent out, once per controller tick. The
// controller is deliberately as simple as the one the thesis collected its turns with, because the
// turns the CKT learns are shaped by it: a better controller would learn different turns.

#include <deque>
#include <optional>

#include "vehicle/vehicle.hpp"

namespace avk::vehicle {

// Gains of one scalar PID. integral_limit bounds the accumulated Ki·e·dt term (its sign ignored).
struct PidGains {
  double kp = 1.0, kd = 0.0, ki = 0.0, integral_limit = 0.0;
};

// The MOOS ScalarPID: the derivative is smoothed over the last few samples because navigation
// headings arrive quantised and jittery; the output is always within ±100 (percent).
class ScalarPid {
 public:
  static constexpr double kOutputLimit = 100.0;
  static constexpr std::size_t kDerivativeWindow = 9;

  explicit ScalarPid(PidGains g = {});

  // One control step for error e at time t_s. Throws std::invalid_argument when t_s is earlier than
  // the previous call's time; at the same time it returns the previous output unchanged.
  double run(double error, double t_s);
  // Forget history, integral and time: the next run() is a first call again.
  void reset();
  const PidGains& gains() const { return gains_; }

  double integral() const { return integral_; }
  double derivative() const { return derivative_; }

 private:
  PidGains gains_;
  bool started_ = false;
  double prev_error_ = 0.0;
  double prev_t_s_ = 0.0;
  double integral_ = 0.0;
  double derivative_ = 0.0;
  double output_ = 0.0;
  std::deque<double> slopes_;  // newest first, at most kDerivativeWindow
};

struct MarinePidConfig {
  PidGains yaw{1, 0, 0, 0};
  PidGains speed{1, 0, 0, 0};
  double max_rudder_pct = 40.0;
  double max_thrust_pct = 100.0;
  // Not zero: thrust = desired speed × speed_factor, open loop (the speed PID is not used).
  double speed_factor = 0.0;
  // Inputs older than this (helm or navigation) stop the vehicle: MOOS tardy_helm/nav_threshold.
  double tardy_s = 2.0;

  // The thesis, Table 5.1 (simulation): yaw and speed P-only with Kp 1, rudder limited to
  // 40 %, incremental speed control. These are the struct defaults.
  static MarinePidConfig thesis_sim();
  // Thesis Table 3.1 (the Kingfisher M200 in the water): yaw Kp 0.5, Ki 0, integral limit 20;
  // speed Kp 1. The thesis gives ranges for the integral settings (Ki 0–0.05, integral limit
  // 10–20). Ki is the lower end: with any integral the yaw integral winds up during a turn and
  // swings the boat 7–26° past its goal, where the thesis describes a gradual approach (§4.5) and
  // establishes the next turn's conditions in 4–8 s (Table 5.2); docs/sim-config.md has the
  // figures. The limit only matters to a user who sets a Ki.
  static MarinePidConfig m200_in_water();
};

// pMarinePID's Iterate, one call per controller tick.
class MarinePid {
 public:
  explicit MarinePid(MarinePidConfig c = {});

  // One controller tick (pMarinePID Iterate) at now_s with the newest navigation and desired values
  // it has seen (each carries its own time). Missing or tardy inputs (older than tardy_s) give all
  // stop: zero thrust and rudder, and the controller restarts from scratch (thrust memory and both
  // PIDs reset) so that integral or derivative state from before the gap cannot jolt the vehicle
  // when inputs return. MOOS keeps its PID state across such a pause; there the integral is the
  // only state that outlives it, and a fresh start is the safer choice for a real boat.
  // Throws std::invalid_argument when now_s goes backwards while inputs are fresh.
  ActuatorCommand step(double now_s, const std::optional<NavSample>& nav,
                       const std::optional<DesiredCommand>& desired);

  void reset();
  const MarinePidConfig& config() const { return config_; }
  // The thrust the incremental speed controller builds on (the previous tick's output).
  double thrust_memory_pct() const { return thrust_memory_pct_; }
  // True when the last step() stopped the vehicle for missing or tardy inputs.
  bool paused() const { return paused_; }

 private:
  MarinePidConfig config_;
  ScalarPid yaw_pid_;
  ScalarPid speed_pid_;
  double thrust_memory_pct_ = 0.0;
  bool paused_ = false;
};

}  // namespace avk::vehicle
