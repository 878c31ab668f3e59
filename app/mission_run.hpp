#pragma once
// A mission run in this process, to its end, on a vehicle of any kind with a source (the
// simulator, paced as fast as it goes or in real time; a real vehicle over its link): started
// from a mission file or resumed from the store. Recorded as the station records a mission on
// its own vehicle; the caller watches through observers.

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/mission_plans.hpp"
#include "app/missions.hpp"
#include "app/result.hpp"
#include "app/vehicle_source.hpp"
#include "mission/mission_observer.hpp"

namespace avk::app {

class Context;

struct MissionRunOptions {
  double max_duration_s = 86400.0;                   // mission clock; interrupted when reached
  const std::atomic<bool>* stop = nullptr;           // raised: interrupted at the next helm tick
  std::vector<mission::MissionObserver*> observers;  // after the recorder, in this order
  // How long a real vehicle may take to send navigation after connecting.
  std::chrono::milliseconds connect_timeout{10000};
  // Told what happens before the run: connecting to a real vehicle (its description), and the
  // plan once the mission is stored.
  std::function<void(const std::string& what)> on_connecting;
  std::function<void(const MissionPlan& plan, int planned)> on_start;
};

struct MissionRunOutcome {
  double start_time_s = 0.0;  // mission clock
  double end_time_s = 0.0;
  double wall_s = 0.0;
  bool stopped = false;    // by the stop flag
  bool simulated = false;  // the vehicle was the simulator's
  int planned = 0;         // turns of the whole plan
  int turns_given_up = 0;
  // Turns the mission finished in this run (ok, aborted or rejected), as its runner counted them.
  int turns_finished = 0;
  std::string link_report;  // a real vehicle's link afterwards (counters, battery)
  MissionSummary summary;   // as stored after the run
};

// Checks the mission file against the vehicle (invalid_argument with every problem; nothing is
// stored), connects a real vehicle (conflict when it sends no navigation; no mission is stored
// for an unreachable vehicle), stores the mission and runs it to its end.
Result<MissionRunOutcome> run_new_mission(Context& ctx, const std::string& config_text,
                                          const VehicleSourceOptions& vehicle,
                                          const MissionRunOptions& options);

// Runs the rest of a stored mission on a vehicle of the kind it ran on (invalid_argument naming
// the kind otherwise; the simulator setup is that of the stored kind unless given). not_found
// for an unknown mission, conflict for one done, aborted or running elsewhere, invalid_argument
// with every problem of a stored mission file the vehicle cannot run.
Result<MissionRunOutcome> resume_mission_run(Context& ctx, std::int64_t mission_id,
                                             VehicleSourceOptions vehicle,
                                             const MissionRunOptions& options);

}  // namespace avk::app
