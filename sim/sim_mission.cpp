#include "sim/sim_mission.hpp"

namespace avk::sim {

namespace {

SchedulerOptions scheduler_options(const SimMissionOptions& o) {
  SchedulerOptions s = o.setup.scheduler;
  s.start_time_s = o.start_time_s;
  return s;
}

}  // namespace

SimVehicleConfig vehicle_at_rest(const SimSetup& setup, const kinematics::Pose& start) {
  SimVehicleConfig v = setup.vehicle;
  v.start_x_m = start.x_m;
  v.start_y_m = start.y_m;
  v.start_heading_deg = start.heading_deg;
  v.start_speed_mps = 0.0;
  v.seed = setup.scheduler.seed;
  return v;
}

SimMission::SimMission(SimMissionOptions options)
    : options_(std::move(options)),
      scheduler_(scheduler_options(options_)),
      vehicle_(vehicle_at_rest(options_.setup, options_.start), scheduler_) {}

SimMissionResult run_helm_on(Scheduler& scheduler, mission::MissionRunner& runner, double helm_hz,
                             double max_duration_s, Pacer& pacer, const std::atomic<bool>* stop,
                             std::function<void(double)> before_tick) {
  SimMissionResult result;
  result.start_time_s = scheduler.now_s();
  const double end = result.start_time_s + max_duration_s;
  scheduler.add("helm", helm_hz, [&](double now) {
    mission::helm_tick(runner, now, end, stop, before_tick, result);
    if (runner.finished()) scheduler.request_stop();
  });
  scheduler.run_until(end + 1.0, pacer);
  result.end_time_s = scheduler.now_s();
  return result;
}

SimMissionResult SimMission::run(mission::MissionRunner& runner, Pacer& pacer,
                                 const std::atomic<bool>* stop,
                                 std::function<void(double)> before_tick) {
  return run_helm_on(scheduler_, runner, options_.setup.helm_hz, options_.max_duration_s, pacer,
                     stop, std::move(before_tick));
}

}  // namespace avk::sim
