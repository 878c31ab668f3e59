#pragma once
// Starting and resuming a stored mission, shared by `avk mission run|resume` and the server:
// validation before anything is stored, the turns still to do, and where the clock continues.

#include <cstdint>
#include <string>
#include <vector>

#include "kinematics/geometry.hpp"
#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"
#include "store/store.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

struct MissionPlan {
  std::int64_t mission_id = 0;
  mission::MissionConfig config;
  std::vector<mission::TurnTask> tasks;  // still to do
  int done_before = 0;                   // ok turns stored before this run
  kinematics::Pose start;                // where a restarted simulator puts the vehicle
  double clock_after_s = 0.0;            // the run's clock starts after this
};

// Validates (mission::MissionConfigError listing every problem; nothing is stored then), stores
// the vehicle and the mission as created.
MissionPlan create_mission_plan(store::Store& db, const std::string& config_text,
                                const vehicle::VehicleInfo& vehicle);

// The remaining turns of a stored mission. Throws std::runtime_error naming why it cannot be
// resumed (unknown, done, aborted, or running in a live process).
MissionPlan resume_mission_plan(store::Store& db, std::int64_t mission_id, double max_speed_mps);

// At rest at the return point, facing the region's interior (the thesis starts dockside).
kinematics::Pose start_pose(const mission::MissionConfig& c);

}  // namespace avk::app
