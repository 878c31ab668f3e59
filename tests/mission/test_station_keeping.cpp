// Station keeping, go-to and stop as pure helm logic, and the command helm on a kinematic point
// vehicle set by a steady current: the closed loop on position holds where an open loop drifts.
#include <gtest/gtest.h>

#include <cmath>

#include "mission/command_helm.hpp"
#include "mission/mission_sim.hpp"
#include "mission/station_keeping.hpp"

using namespace avk::testing::mission_sim;

namespace {

// The kinematic vehicle of the runner's tests, set by a current of (east, north) m/s: navigation
// at 10 Hz, the helm at 5 Hz.
struct DriftLoop {
  FakeVehicle vehicle;
  CommandHelm helm{vehicle};
  k::Point current_mps;
  long k = 0;

  DriftLoop(FakeVehicle v, k::Point current) : vehicle(std::move(v)), current_mps(current) {}

  double now() const { return static_cast<double>(k) * 0.1; }
  double distance_to(k::Point p) const { return k::distance_m({vehicle.x(), vehicle.y()}, p); }
  // Runs for s seconds; the largest distance from `from` seen after each step (none: 0).
  double run_for(double s, std::optional<k::Point> from = std::nullopt) {
    double max_m = 0.0;
    for (const long end = k + std::lround(s * 10.0); k < end; ++k) {
      const double t = now();
      vehicle.step(t);
      vehicle.teleport(vehicle.x() + current_mps.x_m * 0.1, vehicle.y() + current_mps.y_m * 0.1);
      if (k % 2 == 0) helm.tick(t);
      if (from) max_m = std::max(max_m, distance_to(*from));
    }
    return max_m;
  }
  bool until_mode(HelmMode m, double max_s) {
    for (double waited = 0.0; waited < max_s; waited += 0.2) {
      run_for(0.2);
      if (helm.mode() == m) return true;
    }
    return false;
  }
};

NavSample at(double x, double y, double heading = 0.0) {
  return nav_at(0.0, heading, 0.0, x, y);
}

}  // namespace

TEST(StationKeeping, SpeedIsTransitFarOutSlowingDownNearProportionalInsideAndZeroInTheInnerRadius) {
  StationKeepConfig c;
  c.radius_m = 10.0;
  c.inner_fraction = 0.4;
  c.hold_speed_mps = 1.0;
  c.transit_speed_mps = 2.0;
  c.slow_down_m = 20.0;
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(500.0, c), 2.0);
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(30.0, c), 2.0);
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(20.0, c), 1.5);  // halfway through the slow-down
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(10.0, c), 1.0);  // the outer radius: hold speed
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(7.0, c), 0.5);   // proportional past the inner 4 m
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(4.0, c), 0.0);
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(1.0, c), 0.0);
  // A slow transit never speeds up on the way in.
  c.transit_speed_mps = 0.5;
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(15.0, c), 0.5);
  EXPECT_DOUBLE_EQ(station_keep_speed_mps(10.0, c), 0.5);
}

TEST(StationKeeping, HeadsForThePointThenIdlesInsideUntilItDriftsPastTheOuterRadius) {
  StationKeepConfig c;
  c.radius_m = 10.0;
  c.inner_fraction = 0.4;
  StationKeeping sk({100.0, 100.0}, c);
  HelmOutput o = sk.update(at(100.0, 0.0));  // due south of the point
  EXPECT_NEAR(o.heading_deg, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(o.speed_mps, c.transit_speed_mps);
  EXPECT_FALSE(sk.arrived());
  // Facing away, it turns before it goes: half the speed at 90 degrees off and beyond.
  EXPECT_DOUBLE_EQ(sk.update(at(100.0, 0.0, 180.0)).speed_mps, 0.5 * c.transit_speed_mps);
  EXPECT_NEAR(sk.update(at(100.0, 0.0, 30.0)).speed_mps,
              std::cos(avk::kinematics::deg_to_rad(30.0)) * c.transit_speed_mps, 1e-9);
  o = sk.update(at(0.0, 100.0));  // due west
  EXPECT_NEAR(o.heading_deg, 90.0, 1e-9);
  o = sk.update(at(100.0, 97.0));  // inside the inner radius: idle on the last course
  EXPECT_TRUE(sk.arrived());
  EXPECT_TRUE(sk.idle());
  EXPECT_DOUBLE_EQ(o.speed_mps, 0.0);
  EXPECT_NEAR(o.heading_deg, 90.0, 1e-9);
  o = sk.update(at(100.0, 94.0));  // drifting, not yet halfway from 4 m to 10 m: still idle
  EXPECT_TRUE(sk.idle());
  EXPECT_DOUBLE_EQ(o.speed_mps, 0.0);
  o = sk.update(
      at(107.5, 100.0, 270.0));  // past halfway: back towards the point, west, proportional
  EXPECT_FALSE(sk.idle());
  EXPECT_NEAR(o.heading_deg, 270.0, 1e-9);
  EXPECT_NEAR(o.speed_mps, c.hold_speed_mps * (7.5 - 4.0) / 6.0, 1e-9);
  o = sk.update(at(111.0, 100.0, 270.0));  // past the outer radius: faster than the hold speed
  EXPECT_GT(o.speed_mps, c.hold_speed_mps);
  o = sk.update(at(106.0, 100.0, 270.0));  // coming back, inside halfway: steering on, proportional
  EXPECT_FALSE(sk.idle());
  EXPECT_NEAR(o.speed_mps, c.hold_speed_mps * (6.0 - 4.0) / 6.0, 1e-9);
  ASSERT_TRUE(sk.distance_m());
  EXPECT_NEAR(*sk.distance_m(), 6.0, 1e-9);
}

TEST(CommandHelm, HoldsItsPointAgainstACurrentThatCarriesAnIdleBoatAway) {
  const k::Point current{0.25, 0.1};
  DriftLoop idle(FakeVehicle(0, 0, 0), current);
  idle.run_for(600);
  EXPECT_GT(idle.distance_to({0, 0}), 100.0);  // 161 m: what the operator saw

  DriftLoop r(FakeVehicle(0, 0, 0), current);
  VehicleCommand hold;
  hold.kind = VehicleCommandKind::hold;  // here
  r.helm.command(hold, 0.0);
  EXPECT_EQ(r.helm.mode(), HelmMode::transiting);  // no navigation yet: the point is not known
  r.run_for(1.0);
  ASSERT_TRUE(r.helm.active() && r.helm.active()->point);
  const k::Point p = *r.helm.active()->point;
  EXPECT_LT(k::distance_m(p, {0, 0}), 0.5);
  const double max_m = r.run_for(600, p);  // measured 5.03 m: the first swing round
  EXPECT_EQ(r.helm.mode(), HelmMode::holding);
  EXPECT_LE(max_m, hold.radius_m + 1.0) << "max distance " << max_m << " m";
}

TEST(CommandHelm, GoToTransitsAtItsSpeedThenHolds) {
  DriftLoop r(FakeVehicle(0, 0, 0), {0.2, 0.0});
  VehicleCommand go;
  go.kind = VehicleCommandKind::go_to;
  go.point = k::Point{-150.0, 200.0};
  go.speed_mps = 1.8;
  go.radius_m = 8.0;
  r.helm.command(go, 0.0);
  r.run_for(60);
  EXPECT_EQ(r.helm.mode(), HelmMode::transiting);
  ASSERT_TRUE(r.helm.desired_speed_mps());
  EXPECT_NEAR(*r.helm.desired_speed_mps(), 1.8, 0.01);  // on course
  ASSERT_TRUE(r.until_mode(HelmMode::holding, 600));
  EXPECT_LE(r.distance_to(*go.point), go.radius_m);
  EXPECT_TRUE(r.helm.take_arrival());
  EXPECT_FALSE(r.helm.take_arrival());  // once per arrival
  EXPECT_LE(r.run_for(300, *go.point), go.radius_m + 1.0);
}

TEST(CommandHelm, StopSendsAllStopAndTheBoatComesToRest) {
  DriftLoop r(FakeVehicle(0, 0, 0, 1.5), {0.0, 0.0});
  VehicleCommand stop;
  stop.kind = VehicleCommandKind::stop;
  r.helm.command(stop, 0.0);
  r.run_for(10);
  EXPECT_EQ(r.helm.mode(), HelmMode::stopped);
  EXPECT_EQ(r.vehicle.all_stops, 1);
  EXPECT_TRUE(r.vehicle.commands.empty());
  ASSERT_TRUE(r.helm.desired_speed_mps());
  EXPECT_DOUBLE_EQ(*r.helm.desired_speed_mps(), 0.0);
  EXPECT_NEAR(r.vehicle.speed(), 0.0, 1e-9);
}

TEST(CommandHelm, AMissionsEndHoldsAtItsReturnPointAndReturnGoesBackThere) {
  MissionConfig c = turns_config({1.2}, {90}, DirectionPolicy::right, square_region(200, 20));
  c.region.return_point = {30.0, -150.0};
  DriftLoop r(FakeVehicle(0, 0, 0), {0.2, 0.0});
  // Neither a pause nor an interruption moves the vehicle: the mission is not over.
  EXPECT_FALSE(r.helm.mission_ended(c, MissionState::paused, 0.0));
  EXPECT_FALSE(r.helm.mission_ended(c, MissionState::interrupted, 0.0));
  EXPECT_FALSE(r.helm.mode());
  ASSERT_TRUE(r.helm.mission_ended(c, MissionState::done, 0.0));
  ASSERT_TRUE(r.helm.active());
  EXPECT_EQ(r.helm.active()->kind, VehicleCommandKind::return_to);
  EXPECT_EQ(r.helm.active()->point, c.region.return_point);
  r.run_for(20);
  ASSERT_TRUE(r.helm.desired_speed_mps());
  EXPECT_NEAR(*r.helm.desired_speed_mps(), 1.2, 0.01);  // the mission's return speed
  ASSERT_TRUE(r.until_mode(HelmMode::holding, 600));
  EXPECT_LE(r.run_for(300, c.region.return_point), kDefaultHoldRadiusM + 1.0);

  // Sent elsewhere, `return` without a point goes back to the mission's return point.
  VehicleCommand go;
  go.kind = VehicleCommandKind::go_to;
  go.point = k::Point{0.0, 0.0};
  r.helm.command(go, r.now());
  ASSERT_TRUE(r.until_mode(HelmMode::holding, 600));
  VehicleCommand back;
  back.kind = VehicleCommandKind::return_to;
  r.helm.command(back, r.now());
  ASSERT_TRUE(r.helm.active()->point);
  EXPECT_EQ(*r.helm.active()->point, c.region.return_point);
  ASSERT_TRUE(r.until_mode(HelmMode::holding, 600));
  EXPECT_LE(r.distance_to(c.region.return_point), kDefaultHoldRadiusM);
}

TEST(CommandHelm, WithoutNavigationItStopsAndWaits) {
  DriftLoop r(FakeVehicle(0, 0, 0, 1.0), {0.0, 0.0});
  VehicleCommand go;
  go.kind = VehicleCommandKind::go_to;
  go.point = k::Point{0.0, 100.0};
  r.helm.command(go, 0.0);
  r.run_for(5);
  EXPECT_FALSE(r.vehicle.commands.empty());
  r.vehicle.deliver_nav = false;
  r.run_for(5);
  EXPECT_EQ(r.vehicle.all_stops, 1);
  ASSERT_TRUE(r.helm.desired_speed_mps());
  EXPECT_DOUBLE_EQ(*r.helm.desired_speed_mps(), 0.0);
  r.vehicle.deliver_nav = true;
  const std::size_t before = r.vehicle.commands.size();
  r.run_for(2);
  EXPECT_GT(r.vehicle.commands.size(), before);  // steering again
}

TEST(VehicleCommand, DescribesItselfForTheEventLog) {
  VehicleCommand c;
  c.kind = VehicleCommandKind::go_to;
  c.point = k::Point{12.0, -3.5};
  c.speed_mps = 1.5;
  EXPECT_EQ(describe(c), "go_to (12.0, -3.5) at 1.50 m/s, holding within 5.0 m");
  c.kind = VehicleCommandKind::hold;
  c.point.reset();
  c.speed_mps.reset();
  EXPECT_EQ(describe(c), "hold here, holding within 5.0 m");
  c.kind = VehicleCommandKind::stop;
  EXPECT_EQ(describe(c), "all stop");
  for (const auto kind : {VehicleCommandKind::hold, VehicleCommandKind::go_to,
                          VehicleCommandKind::return_to, VehicleCommandKind::stop})
    EXPECT_EQ(vehicle_command_kind_from_string(to_string(kind)), kind);
  EXPECT_EQ(to_string(VehicleCommandKind::return_to), std::string("return"));
}
