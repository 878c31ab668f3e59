#pragma once
// A collection mission against a simulated vehicle: the scheduler, the vehicle and the mission's
// helm as one more AppTick component. Faster than real time or paced to the wall clock, with the
// same code path.

#include <atomic>
#include <functional>
#include <optional>

#include "kinematics/geometry.hpp"
#include "mission/helm_loop.hpp"
#include "mission/mission_runner.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::sim {

// The setup's vehicle at rest at a pose, seeded from the setup's scheduler.
SimVehicleConfig vehicle_at_rest(const SimSetup& setup, const kinematics::Pose& start);

struct SimMissionOptions {
  SimSetup setup{};
  kinematics::Pose start{};       // where the vehicle is when the mission starts, at rest
  double start_time_s = 0.0;      // the mission clock (continues after a resume)
  double max_duration_s = 86400;  // simulated; the mission is interrupted when it is reached
};

using SimMissionResult = mission::HelmLoopResult;

// The runner's helm as one more AppTick component of the scheduler, run until the runner finishes.
// A raised stop flag or the end of max_duration_s (from the scheduler's now) interrupts the
// mission at the next helm tick; before_tick runs at every helm tick before the runner's.
SimMissionResult run_helm_on(Scheduler& scheduler, mission::MissionRunner& runner, double helm_hz,
                             double max_duration_s, Pacer& pacer,
                             const std::atomic<bool>* stop = nullptr,
                             std::function<void(double now_s)> before_tick = {});

class SimMission {
 public:
  explicit SimMission(SimMissionOptions options);

  vehicle::Vehicle& vehicle() { return vehicle_; }
  SimVehicle& sim_vehicle() { return vehicle_; }
  double now_s() const { return scheduler_.now_s(); }

  // Runs until the runner finishes. A raised stop flag (a signal, a server shutdown) or the end
  // of max_duration_s interrupts the mission at the next helm tick. before_tick runs at every
  // helm tick before the runner's, on the simulation thread: the place to apply queued
  // operator commands.
  SimMissionResult run(mission::MissionRunner& runner, Pacer& pacer,
                       const std::atomic<bool>* stop = nullptr,
                       std::function<void(double now_s)> before_tick = {});

 private:
  SimMissionOptions options_;
  Scheduler scheduler_;
  SimVehicle vehicle_;
};

}  // namespace avk::sim
