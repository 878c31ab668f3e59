#include "sim/turn_scenario.hpp"

#include <cmath>
#include <deque>

#include "kinematics/angles.hpp"

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
  std::deque<double> yaw_rates;  // moving average of differenced headings (thesis eq. 4.1-4.2)
  std::optional<vehicle::NavSample> previous;
  std::vector<vehicle::NavSample> recorded;
  double previous_error = 0.0;
  bool timed_out = false;

  const auto finish_turn = [&](double now) {
    std::vector<double> t, x, y, h, v;
    for (const auto& s : recorded) {
      t.push_back(s.t_s);
      x.push_back(s.x_m);
      y.push_back(s.y_m);
      h.push_back(s.heading_deg);
      v.push_back(s.speed_mps);
    }
    kin::TurnMeta meta;
    meta.vehicle_id = vc.id;
    meta.mission_id = "sim-turn";
    meta.commanded_speed_mps = config.speed_mps;
    meta.goal_dheading_deg = config.dheading_deg;
    result.turn = kin::TurnSequence::from_streams(meta, t, x, y, h, v);
    phase = Phase::after;
    phase_start = now;
  };

  scheduler.add("helm", config.helm_hz, [&](double now) {
    for (const auto& s : vehicle.take_nav()) {
      const auto a = vehicle.last_actuators().value_or(vehicle::ActuatorCommand{});
      result.rows.push_back({s.t_s, s.x_m, s.y_m, s.heading_deg, s.speed_mps, desired_heading,
                             config.speed_mps, a.rudder_pct, a.thrust_pct});
      if (previous && s.t_s > previous->t_s) {
        yaw_rates.push_back(kin::angle180_deg(s.heading_deg - previous->heading_deg) /
                            (s.t_s - previous->t_s));
        if (yaw_rates.size() > 5) yaw_rates.pop_front();
      }
      previous = s;
      if (phase == Phase::turning) {
        recorded.push_back(s);
        const double error = kin::angle180_deg(result.goal_heading_deg - s.heading_deg);
        // Complete within the threshold, or when the heading passed the goal between samples.
        const bool passed = recorded.size() > 1 &&
                            std::signbit(error) != std::signbit(previous_error) &&
                            std::abs(error) < 90.0;
        previous_error = error;
        if (std::abs(error) <= config.completion_threshold_deg || passed) finish_turn(now);
      }
    }
    if (phase == Phase::settling && previous) {
      double mean_rate = 0.0;
      for (double r : yaw_rates)
        mean_rate += r;
      if (!yaw_rates.empty()) mean_rate /= static_cast<double>(yaw_rates.size());
      const bool steady =
          std::abs(previous->speed_mps - config.speed_mps) <= config.steady_speed_tolerance_mps &&
          std::abs(mean_rate) <= config.steady_yaw_rate_dps;
      if ((now - phase_start >= config.min_settle_s && steady) ||
          now - phase_start >= config.max_settle_s) {
        phase = Phase::turning;
        phase_start = now;
        result.command_time_s = now;
        result.goal_heading_deg = kin::wrap360_deg(previous->heading_deg + config.dheading_deg);
        desired_heading = result.goal_heading_deg;
        previous_error = kin::angle180_deg(result.goal_heading_deg - previous->heading_deg);
        recorded = {*previous};
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
