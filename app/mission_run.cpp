#include "app/mission_run.hpp"

#include <unistd.h>

#include <chrono>
#include <thread>

#include "app/context.hpp"
#include "app/mission_recorder.hpp"
#include "app/store_access.hpp"
#include "app/store_link.hpp"
#include "mission/helm_loop.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_mission.hpp"

namespace avk::app {

namespace {

// A vehicle a mission runs on here: its scheduler (a simulated vehicle's time, a real vehicle's
// pace) and its source.
struct LocalVehicle {
  explicit LocalVehicle(const VehicleSourceOptions& o)
      : scheduler(scheduler_options(o)), source(make_vehicle_source(o, scheduler)) {}
  sim::Scheduler scheduler;
  std::unique_ptr<VehicleSource> source;
};

Result<std::unique_ptr<LocalVehicle>> open_vehicle(const VehicleSourceOptions& o,
                                                   const MissionRunOptions& options) {
  std::unique_ptr<LocalVehicle> v;
  try {
    v = std::make_unique<LocalVehicle>(o);
  } catch (const std::invalid_argument& e) {
    return invalid_argument("vehicle", e.what());
  }
  if (!vehicle::is_simulated(kind_of(o))) {
    if (options.on_connecting) options.on_connecting(v->source->link_name());
    if (const auto why = v->source->wait_for_nav(options.connect_timeout)) return conflict(*why);
  }
  return v;
}

// Runs the plan to its end on the vehicle, recording it as the station records missions.
Result<MissionRunOutcome> run_on(Context& ctx, const MissionPlan& plan, LocalVehicle& local,
                                 const VehicleSourceOptions& vo, const MissionRunOptions& options) {
  store::Store& db = store_of(ctx);
  VehicleSource& source = *local.source;
  vehicle::Vehicle& vehicle = source.vehicle();
  MissionRecorder recorder(db, plan.mission_id);
  mission::RunnerOptions ro;
  ro.vehicle_id = vehicle.info().id;
  ro.mission_label = std::to_string(plan.mission_id);
  mission::MissionRunner runner(plan.config, vehicle, plan.tasks, ro);
  runner.add_observer(recorder);
  for (auto* o : options.observers)
    runner.add_observer(*o);
  MissionRunOutcome out;
  out.planned = static_cast<int>(mission::plan_turns(plan.config).size());
  out.simulated = source.wall_clock() == nullptr;
  if (options.on_start) options.on_start(plan, out.planned);

  // The process is the mission's runner: if it dies, the mission reads as interrupted.
  recorder.set_runner(static_cast<std::int64_t>(::getpid()));
  const auto wall_start = std::chrono::steady_clock::now();
  mission::HelmLoopResult r;
  if (const vehicle::ScaledClock* clock = source.wall_clock()) {
    // A vehicle that moves by itself: the helm ticks on its clock, starvation not charged.
    r = mission::run_helm_loop(runner, *clock, vo.setup.helm_hz, options.max_duration_s,
                               options.stop);
  } else {
    const std::unique_ptr<sim::Pacer> pacer = source.pacer();
    r = sim::run_helm_on(local.scheduler, runner, vo.setup.helm_hz, options.max_duration_s, *pacer,
                         options.stop);
  }
  source.park();
  out.start_time_s = r.start_time_s;
  out.end_time_s = r.end_time_s;
  out.stopped = r.stopped;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  out.link_report = source.link_report();
  recorder.flush();
  recorder.set_runner(std::nullopt);
  // What the spool still holds goes to the database before the summary reads it; when the server
  // is still away, the summary cannot be read, and the spool is replayed by the next run or serve.
  // What the spool still holds goes to the database before the summary reads it. A server that
  // is away at the end (restarting, a standby being promoted) is waited for a minute; after that
  // the writes stay in the spool for the next run or serve to replay.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!recorder.replay_spool()) {
    if (std::chrono::steady_clock::now() > give_up || (options.stop && options.stop->load()))
      return internal_error(
          "the database is unreachable: " + std::to_string(store_link_view(ctx.db_path()).spooled) +
          " writes wait in the spool " + spool_path());
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  out.turns_given_up = runner.turns_given_up();
  out.turns_finished = recorder.turns_finished();
  auto summary = mission_summary(ctx, plan.mission_id);
  if (!summary) return summary.error();
  out.summary = std::move(*summary);
  return out;
}

// A real vehicle is connected before the plan is stored (an unreachable one leaves no mission
// behind); a simulated one is made where and when the plan starts it.
Result<MissionRunOutcome> plan_and_run(Context& ctx, VehicleSourceOptions vo,
                                       const MissionRunOptions& options,
                                       const std::function<Result<MissionPlan>()>& make_plan) {
  std::unique_ptr<LocalVehicle> real;
  if (!vehicle::is_simulated(kind_of(vo))) {
    vo.start_clock_s = store_of(ctx).missions().station_clock_end_s() + 1.0;
    auto opened = open_vehicle(vo, options);
    if (!opened) return opened.error();
    real = std::move(*opened);
  }
  auto plan = make_plan();
  if (!plan) return plan.error();
  if (real) return run_on(ctx, *plan, *real, vo, options);
  vo.start = plan->start;
  vo.start_clock_s = plan->clock_after_s;
  auto sim = open_vehicle(vo, options);
  if (!sim) return sim.error();
  return run_on(ctx, *plan, **sim, vo, options);
}

}  // namespace

Result<MissionRunOutcome> run_new_mission(Context& ctx, const std::string& config_text,
                                          const VehicleSourceOptions& vehicle,
                                          const MissionRunOptions& options) {
  vehicle::VehicleInfo info;
  try {
    info = planned_vehicle_info(vehicle);
  } catch (const std::invalid_argument& e) {
    return invalid_argument("vehicle", e.what());
  }
  // A mission file with mistakes needs no vehicle to say so.
  if (const auto checked = validate_mission(config_text, info.max_speed_mps); !checked)
    return checked.error();
  return plan_and_run(ctx, vehicle, options,
                      [&] { return create_mission_plan(ctx, config_text, info); });
}

Result<MissionRunOutcome> resume_mission_run(Context& ctx, std::int64_t mission_id,
                                             VehicleSourceOptions vehicle,
                                             const MissionRunOptions& options) {
  store::Store& db = store_of(ctx);
  const auto m = db.missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id) + " in the database");
  const auto stored = db.vehicles().get(m->vehicle_id);
  if (!stored) return not_found("mission's vehicle '" + m->vehicle_id + "' is not stored");
  const auto stored_kind = vehicle::vehicle_kind_from_string(stored->kind);
  const vehicle::VehicleKind kind = kind_of(vehicle);
  if (stored_kind != kind) {
    return invalid_argument("vehicle", "mission " + std::to_string(mission_id) + " ran on " +
                                           stored->kind + ", not on a " + vehicle::to_string(kind) +
                                           ": resume it on a vehicle of its kind");
  }
  // The mission continues on its own vehicle, under its stored id.
  if (vehicle.m200) vehicle.m200->config.id = m->vehicle_id;
  vehicle.setup.vehicle.id = m->vehicle_id;
  double max_speed_mps = 0.0;
  try {
    max_speed_mps = planned_vehicle_info(vehicle).max_speed_mps;
  } catch (const std::invalid_argument& e) {
    return invalid_argument("vehicle", e.what());
  }
  return plan_and_run(ctx, vehicle, options, [&]() -> Result<MissionPlan> {
    auto plan = resume_mission_plan(ctx, mission_id, max_speed_mps);
    if (plan) plan->clock_after_s += 1.0;
    return plan;
  });
}

}  // namespace avk::app
