#include "sim/turn_scenario.hpp"

#include <cmath>

#include "kinematics/angles.hpp"
#include "mission/turn_monitor.hpp"
#include "sim/settle_leg.hpp"

namespace avk::sim {

namespace kin = avk::kinematics;

TurnScenarioResult run_turn_scenario(const TurnScenarioConfig& config, Pacer& pacer) {
  Scheduler scheduler(config.scheduler);
  SimVehicleConfig vc = config.vehicle;
  vc.seed = config.scheduler.seed;
  SimVehicle vehicle(vc, scheduler);
  TurnScenarioResult result;

  enum class Phase { settling, turning, after, done } phase = Phase::settling;
  const double start_heading = vc.start_heading_deg;
  double desired_heading = start_heading;
  double phase_start = 0.0;
  bool timed_out = false;
  // The mission's own ConditionSet and turn recorder, so `avk sim turn` starts and ends a turn
  // exactly as a mission does.
  SettleLeg settle({.min_settle_s = config.min_settle_s,
                    .max_settle_s = config.max_settle_s,
                    .speed_tolerance_mps = config.steady_speed_tolerance_mps,
                    .max_yaw_rate_dps = config.steady_yaw_rate_dps},
                   config.speed_mps);
  std::optional<mission::TurnMonitor> monitor;

  const auto finish_turn = [&](double now) {
    result.turn = monitor->build(vc.id, "sim-turn");
    phase = Phase::after;
    phase_start = now;
  };

  scheduler.add("helm", config.helm_hz, [&](double now) {
    for (const auto& s : vehicle.take_nav()) {
      const auto a = vehicle.last_actuators().value_or(vehicle::ActuatorCommand{});
      result.rows.push_back({s.t_s, s.x_m, s.y_m, s.heading_deg, s.speed_mps, desired_heading,
                             config.speed_mps, a.rudder_pct, a.thrust_pct});
      settle.update(s);
      if (phase == Phase::turning && monitor->update(s) != mission::Completion::none) {
        finish_turn(now);
      }
    }
    if (phase == Phase::settling) {
      if (settle.done(now)) {
        phase = Phase::turning;
        phase_start = now;
        result.command_time_s = now;
        monitor.emplace(*settle.newest(), config.speed_mps, config.dheading_deg, config.completion);
        result.goal_heading_deg = monitor->goal_heading_deg();
        desired_heading = result.goal_heading_deg;
      }
    } else if (phase == Phase::turning && now - phase_start > config.timeout_s) {
      timed_out = true;
      finish_turn(now);
    } else if (phase == Phase::after) {
      if (now - phase_start >= config.after_turn_s) {
        phase = Phase::done;
        scheduler.request_stop();
      }
    }
    vehicle.command({now, desired_heading, config.speed_mps});
  });
  const double horizon = config.max_settle_s + config.timeout_s + config.after_turn_s + 10.0;
  scheduler.run_until(horizon, pacer);
  result.completed = !timed_out && phase == Phase::done;
  return result;
}

TurnScenarioResult run_turn_scenario(const TurnScenarioConfig& config) {
  FastPacer fast;
  return run_turn_scenario(config, fast);
}

}  // namespace avk::sim
