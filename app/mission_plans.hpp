#pragma once
// Starting and resuming a stored mission, shared by `avk mission run|resume` and the server:
// validation before anything is stored, the turns still to do, and where the clock continues.

#include <cstdint>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/geometry.hpp"
#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

class Context;

struct MissionPlan {
  std::int64_t mission_id = 0;
  mission::MissionConfig config;
  std::vector<mission::TurnTask> tasks;  // still to do
  int done_before = 0;                   // ok turns stored before this run
  kinematics::Pose start;                // where a restarted simulator puts the vehicle
  double clock_after_s = 0.0;            // the run's clock starts after this
};

// invalid_argument with every problem the mission file has.
Error mission_config_error(const mission::MissionConfigError& e);

// Validates (invalid_argument listing every problem; nothing is stored then), stores the vehicle
// and the mission as created.
Result<MissionPlan> create_mission_plan(Context& ctx, const std::string& config_text,
                                        const vehicle::VehicleInfo& vehicle);

// The remaining turns of a stored mission: not_found for an unknown one, conflict naming why it
// cannot be resumed (done, aborted, or running in a live process), invalid_argument with every
// problem of its stored file on a vehicle of max_speed_mps.
Result<MissionPlan> resume_mission_plan(Context& ctx, std::int64_t mission_id,
                                        double max_speed_mps);

// At rest at the return point, facing the region's interior (the thesis starts dockside).
kinematics::Pose start_pose(const mission::MissionConfig& c);

}  // namespace avk::app
