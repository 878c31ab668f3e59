#include "app/mission_plans.hpp"

#include <stdexcept>

#include "app/context.hpp"
#include "app/mission_liveness.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "mission/container.hpp"
#include "mission/event_kind.hpp"

namespace avk::app {

kinematics::Pose start_pose(const mission::MissionConfig& c) {
  const mission::Container container(c.region);
  const auto rp = c.region.return_point;
  const auto in = container.interior_point();
  const double heading = kinematics::distance_m(rp, in) > 1e-6
                             ? kinematics::heading_of_deg(in.x_m - rp.x_m, in.y_m - rp.y_m)
                             : 0.0;
  return {rp.x_m, rp.y_m, heading};
}

Error mission_config_error(const mission::MissionConfigError& e) {
  Error out = invalid_argument("", "the mission is not valid");
  for (const auto& f : e.errors())
    out.fields.push_back({f.field, f.message});
  return out;
}

Result<MissionPlan> create_mission_plan(Context& ctx, const std::string& config_text,
                                        const vehicle::VehicleInfo& vehicle) {
  store::Store& db = store_of(ctx);
  MissionPlan p;
  try {
    p.config = mission::parse_mission_config(config_text, vehicle.max_speed_mps);
  } catch (const mission::MissionConfigError& e) {
    return mission_config_error(e);
  }
  // Everything that can fail is done before the mission is stored: a start that throws must not
  // leave a row behind (the validation bounds the plan, so planning is cheap).
  p.tasks = mission::plan_turns(p.config);
  p.start = start_pose(p.config);
  db.vehicles().upsert(vehicle);
  p.mission_id = db.missions().create(vehicle.id, p.config.name, config_text);
  return p;
}

Result<MissionPlan> resume_mission_plan(Context& ctx, std::int64_t mission_id,
                                        double max_speed_mps) {
  store::Store& db = store_of(ctx);
  const auto m = db.missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id) + " in the database");
  const store::MissionStatus status = effective_status(*m);
  if (status == store::MissionStatus::done || status == store::MissionStatus::aborted) {
    return conflict("mission " + std::to_string(m->id) + " is " + store::to_string(status) +
                        "; there is nothing to resume",
                    m->id);
  }
  if (status == store::MissionStatus::running) {
    return conflict("mission " + std::to_string(m->id) + " is running in process " +
                        std::to_string(m->runner_pid.value_or(0)),
                    m->id);
  }
  MissionPlan p;
  p.mission_id = m->id;
  try {
    p.config = mission::parse_mission_config(m->config_json, max_speed_mps);
  } catch (const mission::MissionConfigError& e) {
    return mission_config_error(e);
  }
  std::vector<mission::CellCount> done;
  for (const auto& c : db.missions().cell_stats(m->id)) {
    done.push_back({c.speed_mps, c.dheading_deg, static_cast<int>(c.n_ok), c.speed_after_mps});
    p.done_before += static_cast<int>(c.n_ok);
  }
  p.tasks = mission::remaining_turns(mission::plan_turns(p.config), done);
  p.clock_after_s = db.missions().clock_end_s(m->id).value_or(0.0);
  // A restarted simulator puts the vehicle where it was last seen; its motion is not stored.
  const auto nav = db.navigation().for_mission(m->id);
  p.start = nav.empty() ? start_pose(p.config)
                        : kinematics::Pose{nav.back().x_m, nav.back().y_m, nav.back().heading_deg};
  db.missions().append_event(m->id, p.clock_after_s + 1.0,
                             std::string(mission::to_string(mission::EventKind::resume)),
                             "resumed from " + std::string(store::to_string(status)) + " with " +
                                 std::to_string(p.tasks.size()) + " turns to do");
  return p;
}

}  // namespace avk::app
