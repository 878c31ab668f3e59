#pragma once
// The helm's AppTick against a vehicle on the network: the runner ticks at helm_hz on the run's
// clock (wall clock x a factor), on the calling thread, until the mission finishes, a stop flag
// is raised or the time limit passes. The simulator has its own scheduler (sim/sim_mission.hpp);
// this loop is for vehicles that move by themselves.

#include <atomic>
#include <functional>

#include "mission/mission_runner.hpp"
#include "vehicle/scaled_clock.hpp"

namespace avk::mission {

struct HelmLoopResult {
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  bool stopped = false;          // the stop flag was raised
  bool horizon_reached = false;  // max_duration_s ran out
};

// One helm tick at now_s, shared by this loop and the simulator's scheduler: a raised stop flag
// or the passing of end_s interrupts the mission (recorded in result); otherwise before_tick
// (operator commands queued from other threads) and the runner's tick.
void helm_tick(MissionRunner& runner, double now_s, double end_s, const std::atomic<bool>* stop,
               const std::function<void(double now_s)>& before_tick, HelmLoopResult& result);

// A tick that comes due while the previous one is still running is skipped, not made up: a late
// helm acts on the newest navigation anyway. before_tick runs before each of the runner's ticks
// (operator commands queued from other threads).
HelmLoopResult run_helm_loop(MissionRunner& runner, const vehicle::ScaledClock& clock,
                             double helm_hz, double max_duration_s,
                             const std::atomic<bool>* stop = nullptr,
                             const std::function<void(double now_s)>& before_tick = {});

}  // namespace avk::mission
