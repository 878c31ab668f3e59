#pragma once
// One steady-then-turn run of a simulated vehicle: hold course 0 at speed U until steady, command
// a constant new heading (current heading + dheading) and speed, record until the heading is
// reached. What `avk sim turn` prints and what `avk sim variability` repeats.

#include <optional>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "mission/mission_config.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::sim {

struct TurnScenarioConfig {
  SimVehicleConfig vehicle = sim_vehicle_defaults(vehicle::VehicleKind::usim);
  SchedulerOptions scheduler{};
  double speed_mps = 1.0;
  double dheading_deg = 90.0;  // signed: + right
  double helm_hz = 4.0;        // pHelmIvP AppTick
  double recorder_hz = 0.0;    // 0: record every navigation sample as it arrives at the helm
  double min_settle_s = 20.0;  // hold course at least this long before the turn
  double max_settle_s = 300.0;
  double steady_speed_tolerance_mps = 0.05;
  double steady_yaw_rate_dps = 1.0;
  // The mission's rule (relative to the commanded change) with a tighter 2 deg bound, so the
  // printed turn runs closer to its goal than a mission's.
  mission::CompletionRule completion{2.0, 0.1, 1.0};
  double after_turn_s = 10.0;  // keep running (and printing) after the turn completes
  double timeout_s = 300.0;    // the turn itself
};

struct TrajectoryRow {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  double desired_heading_deg = 0.0;
  double desired_speed_mps = 0.0;
  double rudder_pct = 0.0;
  double thrust_pct = 0.0;
};

struct TurnScenarioResult {
  std::vector<TrajectoryRow> rows;  // every navigation sample of the run
  kinematics::TurnSequence turn;    // from the command to completion
  double command_time_s = 0.0;
  double goal_heading_deg = 0.0;
  bool completed = false;
};

TurnScenarioResult run_turn_scenario(const TurnScenarioConfig& config, Pacer& pacer);
TurnScenarioResult run_turn_scenario(const TurnScenarioConfig& config);

}  // namespace avk::sim
