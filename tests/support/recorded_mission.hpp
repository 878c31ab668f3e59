#pragma once
// A collection mission on the simulated usim, recorded as the station records it, on the
// simulator's own scheduler (no wall clock, so no dependence on the machine's load).

#include <cstdint>
#include <string>

#include "app/mission_plans.hpp"
#include "app/mission_recorder.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"
#include "store/store.hpp"

namespace avk::testing {

// Two speeds x two heading changes, twice each, on a wide region.
inline constexpr const char* kSmallMission = R"({
  "name": "small",
  "turn_array": {"speeds_mps": [1.0, 1.5], "dheadings_deg": [40, 90], "repeats": 2},
  "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                       "buffer_m": 25, "return_point_m": [0, -70]}})";

inline std::int64_t run_recorded_mission(store::Store& db, const std::string& vehicle_id,
                                         const std::string& mission_text = kSmallMission,
                                         sim::SimSetup setup = sim::default_sim_setup("usim")) {
  sim::SimMissionOptions so;
  so.setup = std::move(setup);
  so.setup.vehicle.id = vehicle_id;
  const auto config = mission::parse_mission_config(mission_text, 2.0);
  so.start = app::start_pose(config);
  // The mission clock continues after everything stored, as the station's does.
  so.start_time_s = db.missions().station_clock_end_s() + 1.0;
  sim::SimMission sim(so);
  // Stored as create_mission_plan stores it (the use case wants a station Context; the callers
  // hold a bare Store).
  app::MissionPlan plan;
  plan.config = config;
  plan.tasks = mission::plan_turns(config);
  db.vehicles().upsert(sim.vehicle().info());
  plan.mission_id = db.missions().create(vehicle_id, config.name, mission_text);
  mission::RunnerOptions ro;
  ro.vehicle_id = vehicle_id;
  mission::MissionRunner runner(plan.config, sim.vehicle(), plan.tasks, ro);
  app::MissionRecorder recorder(db, plan.mission_id);
  runner.add_observer(recorder);
  sim::FastPacer pacer;
  sim.run(runner, pacer, nullptr);
  recorder.flush();
  return plan.mission_id;
}

}  // namespace avk::testing
