#include "app/mission_run.hpp"

#include <unistd.h>

#include <chrono>

#include "app/context.hpp"
#include "app/mission_recorder.hpp"
#include "mission/helm_loop.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_mission.hpp"

namespace avk::app {

Result<MissionRunOutcome> run_mission_here(Context& ctx, const MissionPlan& plan,
                                           LocalVehicle& local, const MissionRunOptions& options) {
  if ((local.m200 == nullptr) != (local.clock == nullptr))
    return invalid_argument("vehicle", "an M200 needs its clock");
  store::Store& db = ctx.db();
  std::optional<sim::SimMission> sim;
  if (!local.m200) {
    sim::SimMissionOptions so;
    so.setup = local.setup;
    so.start = plan.start;
    so.start_time_s = plan.clock_after_s;
    so.max_duration_s = options.max_duration_s;
    sim.emplace(so);
  }
  vehicle::Vehicle& vehicle =
      local.m200 ? static_cast<vehicle::Vehicle&>(*local.m200) : sim->vehicle();
  MissionRecorder recorder(db, plan.mission_id);
  mission::RunnerOptions ro;
  ro.vehicle_id = local.id;
  ro.mission_label = std::to_string(plan.mission_id);
  mission::MissionRunner runner(plan.config, vehicle, plan.tasks, ro);
  runner.add_observer(recorder);
  for (auto* o : options.observers)
    runner.add_observer(*o);

  // The process is the mission's runner: if it dies, the mission reads as interrupted.
  db.missions().set_runner(plan.mission_id, static_cast<std::int64_t>(::getpid()));
  MissionRunOutcome out;
  const auto wall_start = std::chrono::steady_clock::now();
  if (local.m200) {
    const auto r = mission::run_helm_loop(runner, *local.clock, local.setup.helm_hz,
                                          options.max_duration_s, options.stop);
    out.start_time_s = r.start_time_s;
    out.end_time_s = r.end_time_s;
    out.stopped = r.stopped;
    // Leave the vehicle stopped by our own command, not by the frontseat's watchdog.
    local.m200->all_stop(local.clock->now_s());
    local.clock->sleep_until(local.clock->now_s() + 3.0 / local.controller_hz);
  } else {
    std::unique_ptr<sim::Pacer> pacer;
    if (local.realtime)
      pacer = std::make_unique<sim::RealtimePacer>(local.realtime_factor);
    else
      pacer = std::make_unique<sim::FastPacer>();
    const auto r = sim->run(runner, *pacer, options.stop);
    out.start_time_s = r.start_time_s;
    out.end_time_s = r.end_time_s;
    out.stopped = r.stopped;
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  recorder.flush();
  db.missions().set_runner(plan.mission_id, std::nullopt);
  out.planned = static_cast<int>(mission::plan_turns(plan.config).size());
  out.turns_given_up = runner.turns_given_up();
  auto summary = mission_summary(ctx, plan.mission_id);
  if (!summary) return summary.error();
  out.summary = std::move(*summary);
  return out;
}

}  // namespace avk::app
