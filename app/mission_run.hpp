#pragma once
// A mission run in this process, to its end, on a vehicle the caller owns: the simulator (paced
// as fast as it goes, or in real time) or an M200 over its frontseat link. Recorded as the
// station records a mission on its own vehicle; the caller watches through observers.

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "app/mission_plans.hpp"
#include "app/missions.hpp"
#include "app/result.hpp"
#include "mission/mission_observer.hpp"
#include "sim/sim_config.hpp"
#include "vehicle/m200.hpp"
#include "vehicle/scaled_clock.hpp"

namespace avk::app {

class Context;

struct LocalVehicle {
  std::string id;
  // The simulated vehicle (and the helm rate for either kind).
  sim::SimSetup setup;
  bool realtime = false;  // the simulator paced to the wall clock x realtime_factor
  double realtime_factor = 1.0;
  // Set: the mission drives this connected M200 on its clock instead of the simulator.
  vehicle::M200* m200 = nullptr;
  const vehicle::ScaledClock* clock = nullptr;
  double controller_hz = 10.0;  // the M200's controller rate: how long its last command takes
};

struct MissionRunOptions {
  double max_duration_s = 86400.0;                   // mission clock; interrupted when reached
  const std::atomic<bool>* stop = nullptr;           // raised: interrupted at the next helm tick
  std::vector<mission::MissionObserver*> observers;  // after the recorder, in this order
};

struct MissionRunOutcome {
  double start_time_s = 0.0;  // mission clock
  double end_time_s = 0.0;
  double wall_s = 0.0;
  bool stopped = false;  // by the stop flag
  int planned = 0;       // turns of the whole plan
  int turns_given_up = 0;
  MissionSummary summary;  // as stored after the run
};

Result<MissionRunOutcome> run_mission_here(Context& ctx, const MissionPlan& plan,
                                           LocalVehicle& vehicle, const MissionRunOptions& options);

}  // namespace avk::app
