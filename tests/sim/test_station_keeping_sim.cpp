// The commanded helm and a mission's start and end closed around the simulated M200 in
// examples/sim-choppy.json (0.2 m/s current, 5 m/s wind with gusts, sensor noise), on the
// simulator's seeded clock: holding, going to a point, returning, a start far outside the region
// and the hold after a mission's end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>

#include "kinematics/geometry.hpp"
#include "mission/command_helm.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"
#include "support/example_file.hpp"

namespace {

using namespace avk;
using mission::HelmMode;
using mission::VehicleCommand;
using mission::VehicleCommandKind;
namespace k = avk::kinematics;

// The simulated M200 at rest at `start`: a mission's runner while one runs, else the command
// helm, as the station's vehicle loop drives them; the mission's end hands over to the helm.
struct Boat {
  sim::SimSetup setup =
      sim::parse_sim_config(avk::testing::example_text("sim-choppy.json"), "m200");
  sim::Scheduler scheduler{setup.scheduler};
  sim::SimVehicle vehicle;
  mission::CommandHelm helm{vehicle};
  std::optional<mission::MissionConfig> config;
  std::unique_ptr<mission::MissionRunner> runner;
  std::vector<HelmMode> runner_modes;
  sim::FastPacer pacer;
  // The largest distance from `watch` at a helm tick since it was set.
  std::optional<k::Point> watch;
  double max_distance_m = 0.0;

  explicit Boat(k::Pose start) : vehicle(sim::vehicle_at_rest(setup, start), scheduler) {
    scheduler.add("helm", setup.helm_hz, [this](double now) { tick(now); });
  }

  void tick(double now) {
    if (runner && !runner->finished()) {
      runner->tick(now);
      if (runner_modes.empty() || runner_modes.back() != runner->mode())
        runner_modes.push_back(runner->mode());
      if (runner->finished()) helm.mission_ended(*config, *runner->state(), now);
    } else {
      helm.tick(now);
    }
    if (const auto nav = vehicle.last_nav(); nav && watch)
      max_distance_m = std::max(max_distance_m, k::distance_m({nav->x_m, nav->y_m}, *watch));
  }

  k::Point position() const { return {vehicle.last_nav()->x_m, vehicle.last_nav()->y_m}; }
  double distance_to(k::Point p) const { return k::distance_m(position(), p); }
  void run_for(double s) { scheduler.run_until(scheduler.now_s() + s, pacer); }
  // Runs in one-second steps until done() holds, at most max_s.
  template <class F>
  bool run_until(F done, double max_s) {
    for (double t = 0.0; t < max_s; t += 1.0) {
      run_for(1.0);
      if (done()) return true;
    }
    return false;
  }
  // The largest distance from p over s seconds from now.
  double max_distance_over(k::Point p, double s) {
    watch = p;
    max_distance_m = 0.0;
    run_for(s);
    watch.reset();
    return max_distance_m;
  }
  void command(VehicleCommand c) { helm.command(c, scheduler.now_s()); }
};

VehicleCommand hold_here(double radius_m) {
  VehicleCommand c;
  c.kind = VehicleCommandKind::hold;
  c.radius_m = radius_m;
  return c;
}

}  // namespace

TEST(StationKeepingSim, TheM200DriftsAwayInChoppyConditionsWhenNothingHoldsIt) {
  Boat boat({0.0, 0.0, 0.0});
  boat.run_for(600);
  EXPECT_GT(boat.distance_to({0.0, 0.0}), 60.0);  // the current alone carries it 120 m
}

TEST(StationKeepingSim, HoldKeepsTheM200WithinTenMetresForTenMinutesInChoppyConditions) {
  Boat boat({0.0, 0.0, 0.0});
  boat.run_for(1.0);  // the first navigation
  boat.command(hold_here(5.0));
  ASSERT_TRUE(boat.helm.active()->point);
  const k::Point p = *boat.helm.active()->point;
  ASSERT_TRUE(boat.run_until([&] { return boat.helm.mode() == HelmMode::holding; }, 60));
  const double max_m = boat.max_distance_over(p, 600);
  std::printf("hold: max distance %.2f m over 10 simulated minutes\n", max_m);
  EXPECT_LE(max_m, 10.0);
  EXPECT_EQ(boat.helm.mode(), HelmMode::holding);
}

TEST(StationKeepingSim, GoToArrivesWithinItsRadiusThenHolds) {
  Boat boat({0.0, 0.0, 0.0});
  VehicleCommand go;
  go.kind = VehicleCommandKind::go_to;
  go.point = k::Point{-120.0, 160.0};  // across the wind and the current
  go.speed_mps = 1.5;
  go.radius_m = 6.0;
  boat.command(go);
  boat.run_for(30);
  EXPECT_EQ(boat.helm.mode(), HelmMode::transiting);
  ASSERT_TRUE(boat.run_until([&] { return boat.helm.mode() == HelmMode::holding; }, 600));
  EXPECT_LE(boat.distance_to(*go.point), go.radius_m + 1.0);  // navigation is a step behind
  boat.run_for(60);  // the run in slows down past the point
  const double max_m = boat.max_distance_over(*go.point, 300);
  std::printf("go-to: max distance %.2f m over 5 simulated minutes of holding\n", max_m);
  EXPECT_LE(max_m, 10.0);
}

TEST(StationKeepingSim, ReturnGoesBackToTheLastMissionsReturnPointAndHolds) {
  Boat boat({0.0, 0.0, 0.0});
  mission::MissionConfig c;
  c.region.return_point = {80.0, -60.0};
  boat.helm.mission_started(c);
  VehicleCommand back;
  back.kind = VehicleCommandKind::return_to;
  boat.command(back);
  ASSERT_TRUE(boat.helm.active()->point);
  EXPECT_EQ(*boat.helm.active()->point, c.region.return_point);
  ASSERT_TRUE(boat.run_until([&] { return boat.helm.mode() == HelmMode::holding; }, 600));
  EXPECT_LE(boat.distance_to(c.region.return_point), back.radius_m + 1.0);
  boat.run_for(60);  // the run in slows down past the point
  const double max_m = boat.max_distance_over(c.region.return_point, 300);
  std::printf("return: max distance %.2f m over 5 simulated minutes of holding\n", max_m);
  EXPECT_LE(max_m, 10.0);
}

TEST(StationKeepingSim, StopBringsTheM200ToRest) {
  Boat boat({0.0, 0.0, 0.0});
  VehicleCommand go;
  go.kind = VehicleCommandKind::go_to;
  go.point = k::Point{0.0, 500.0};
  boat.command(go);
  boat.run_for(60);
  ASSERT_GT(boat.vehicle.last_nav()->speed_mps, 0.8);
  VehicleCommand stop;
  stop.kind = VehicleCommandKind::stop;
  boat.command(stop);
  boat.run_for(60);
  EXPECT_EQ(boat.helm.mode(), HelmMode::stopped);
  // Over ground it moves with the current (0.2 m/s) and the wind's drift, no faster.
  EXPECT_LT(boat.vehicle.last_nav()->speed_mps, 0.45);
}

TEST(StationKeepingSim, AMissionStarted300mOutsideItsRegionTransitsRunsItsTurnsAndHoldsAfter) {
  const std::string text = R"({
    "name": "far-start",
    "turn_array": {"speeds_mps": [1.0], "dheadings_deg": [45, 90], "repeats": 1},
    "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                         "buffer_m": 25, "return_point_m": [0, -70]}})";
  Boat boat({0.0, -400.0, 180.0});  // 300 m south of the region, facing away
  boat.config = mission::parse_mission_config(text, boat.setup.vehicle_max_speed_mps());
  boat.runner = std::make_unique<mission::MissionRunner>(
      *boat.config, boat.vehicle, mission::plan_turns(*boat.config),
      mission::RunnerOptions{"sim-m200", "far-start"});
  boat.helm.mission_started(*boat.config);
  ASSERT_TRUE(boat.run_until([&] { return boat.runner->finished(); }, 3600));
  EXPECT_EQ(boat.runner->state(), mission::MissionState::done);
  ASSERT_GE(boat.runner_modes.size(), 3u);
  EXPECT_EQ(boat.runner_modes[0], HelmMode::transiting);
  EXPECT_NE(std::find(boat.runner_modes.begin(), boat.runner_modes.end(), HelmMode::turning),
            boat.runner_modes.end());
  int ok = 0;
  for (const auto& c : boat.runner->cells())
    ok += c.ok;
  EXPECT_EQ(ok, 2);
  // The mission's end: held at its return point, not left to drift.
  EXPECT_EQ(boat.helm.active()->kind, VehicleCommandKind::return_to);
  const k::Point rp = boat.config->region.return_point;
  const double max_m = boat.max_distance_over(rp, 300);
  std::printf("after done: max distance %.2f m from the return point over 5 minutes\n", max_m);
  EXPECT_LE(max_m, 10.0);
  EXPECT_EQ(boat.helm.mode(), HelmMode::holding);
}
