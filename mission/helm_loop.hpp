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
  // Clock time the loop was starved of (not charged to max_duration_s; see run_helm_loop).
  double starved_s = 0.0;
};

// One helm tick at now_s, shared by this loop and the simulator's scheduler: a raised stop flag
// or the passing of end_s interrupts the mission (recorded in result); otherwise before_tick
// (operator commands queued from other threads) and the runner's tick.
void helm_tick(MissionRunner& runner, double now_s, double end_s, const std::atomic<bool>* stop,
               const std::function<void(double now_s)>& before_tick, HelmLoopResult& result);

// Ticks further apart than this many helm periods mean the loop's thread was starved.
inline constexpr double kStarvedAfterTicks = 4.0;

// A tick that comes due while the previous one is still running is skipped, not made up: a late
// helm acts on the newest navigation anyway. before_tick runs before each of the runner's ticks
// (operator commands queued from other threads).
//
// max_duration_s is a budget of the time the helm was there to steer, not of the clock alone:
// when ticks are more than kStarvedAfterTicks periods apart, the thread was starved (a loaded
// machine, a debugger; at 10x a 0.1 s stall is a second of mission), and the gap beyond one
// period is not charged. A mission could do nothing with that time, so a correct mission that
// needs D seconds of steering always meets a budget above D, however loaded the machine; a
// mission that never finishes still meets its limit, since a loop that ticks is charged in full.
HelmLoopResult run_helm_loop(MissionRunner& runner, const vehicle::ScaledClock& clock,
                             double helm_hz, double max_duration_s,
                             const std::atomic<bool>* stop = nullptr,
                             const std::function<void(double now_s)>& before_tick = {});

}  // namespace avk::mission
