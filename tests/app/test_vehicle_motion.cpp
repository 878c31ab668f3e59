// What the station learns of how a vehicle moves on a held heading: the steady stretches before
// the commands leave out the last turn's tail and the speed loop's recovery; the simulated M200
// (pMarinePID on the speed over ground) is identified as holding the speed over ground, and the
// same hull with its thrust mapped open loop from the commanded speed as holding it through the
// water; the vehicle's answer takes the newest identification, pools the drift scatter and falls
// back to the defaults.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/mission_legs.hpp"
#include "app/store_access.hpp"
#include "app/vehicle_motion.hpp"
#include "kinematics/angles.hpp"
#include "support/example_file.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
namespace kin = avk::kinematics;

// 10 Hz navigation under one desired heading and speed from t0: the heading swings in from
// `from_deg` to `to_deg` over turn_s and the speed over ground ramps from ramp_from_mps to speed
// over ramp_s, then both hold.
std::vector<store::NavRow> leg_rows(double t0, double duration_s, double from_deg, double to_deg,
                                    double turn_s, double speed, double ramp_from_mps,
                                    double ramp_s) {
  std::vector<store::NavRow> rows;
  double x = 0.0, y = 0.0;
  for (double t = 0.0; t < duration_s - 1e-9; t += 0.1) {
    const double heading = t < turn_s ? from_deg + (to_deg - from_deg) * t / turn_s : to_deg;
    const double v = t < ramp_s ? ramp_from_mps + (speed - ramp_from_mps) * t / ramp_s : speed;
    store::NavRow r;
    r.t_s = t0 + t;
    r.x_m = x;
    r.y_m = y;
    r.heading_deg = kin::wrap360_deg(heading);
    r.speed_mps = v;
    r.desired_heading_deg = to_deg;
    r.desired_speed_mps = speed;
    r.helm_mode = "turn";
    rows.push_back(r);
    x += 0.1 * v * std::sin(kin::deg_to_rad(heading));
    y += 0.1 * v * std::cos(kin::deg_to_rad(heading));
  }
  return rows;
}

TEST(SteadyStretches, TheTurnsTailAndTheSpeedRecoveryAreLeftOut) {
  // 6 s swinging in from 60 deg to north, then 24 s steady: the command comes at t = 130.
  const auto rows = leg_rows(100.0, 30.0, 60.0, 0.0, 6.0, 1.0, 1.0, 0.0);
  const auto legs = app::steady_stretches_before({130.0}, rows);
  ASSERT_EQ(legs.size(), 1u);
  const kin::SteadyLeg& l = legs[0];
  // The heading comes within 8 deg of north at 6 × 52/60 = 5.2 s; the 1 s smoothing lets the
  // judged mean in half a second earlier at most.
  EXPECT_GE(l.t_s.front(), 104.5);
  EXPECT_LE(l.t_s.front(), 105.5);
  EXPECT_NEAR(l.t_s.back(), 129.9, 1e-9);
  EXPECT_NEAR(l.water_speed_mps, 1.0, 1e-12);
  EXPECT_LT(std::abs(kin::angle180_deg(l.heading_deg)), 1.0);
  // Longer than the current's 8 s: the whole steady stretch.
  EXPECT_GT(l.t_s.back() - l.t_s.front(), 20.0);

  // A speed ramp from 0.5 m/s over 10 s: kept from where the speed is within 0.05 m/s of 1.0.
  const auto ramp = leg_rows(100.0, 30.0, 0.0, 0.0, 0.0, 1.0, 0.5, 10.0);
  const auto ramped = app::steady_stretches_before({130.0}, ramp);
  ASSERT_EQ(ramped.size(), 1u);
  EXPECT_GE(ramped[0].t_s.front(), 108.5);
  EXPECT_LE(ramped[0].t_s.front(), 109.6);
}

TEST(SteadyStretches, AtMostAMinuteAtLeastFiveSecondsAndOneGuidance) {
  const auto rows = leg_rows(0.0, 200.0, 0.0, 0.0, 0.0, 1.5, 1.5, 0.0);
  const auto legs = app::steady_stretches_before({150.0}, rows);
  ASSERT_EQ(legs.size(), 1u);
  EXPECT_NEAR(legs[0].t_s.back() - legs[0].t_s.front(), app::kMotionLegMaxS - 0.1, 0.11);
  // Steady for only 4 s before the command: no leg.
  const auto short_rows = leg_rows(0.0, 10.0, 90.0, 0.0, 6.0, 1.0, 1.0, 0.0);
  EXPECT_TRUE(app::steady_stretches_before({10.0}, short_rows).empty());
  // A change of the desired heading starts the stretch, however steady the vehicle was before.
  auto two = leg_rows(0.0, 20.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0);
  auto after = leg_rows(20.0, 10.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0);
  for (auto& r : after)
    r.desired_heading_deg = 2.0;
  two.insert(two.end(), after.begin(), after.end());
  const auto split = app::steady_stretches_before({30.0}, two);
  ASSERT_EQ(split.size(), 1u);
  EXPECT_NEAR(split[0].t_s.front(), 20.0, 1e-9);
  // No guidance at the command, or none before it: nothing.
  EXPECT_TRUE(app::steady_stretches_before({0.0}, rows).empty());
  auto unguided = rows;
  for (auto& r : unguided)
    r.desired_speed_mps.reset();
  EXPECT_TRUE(app::steady_stretches_before({150.0}, unguided).empty());
}

// The M200's speed loop (pMarinePID on the GNSS speed) in 0.3 m/s: identified over ground, by the
// recorder as the mission runs and by the estimate afterwards; the vehicle's answer says so.
TEST(VehicleMotion, TheSimulatedM200HoldsTheSpeedOverGround) {
  avk::testing::TempDb db("avk_app_motion_og");
  app::Context ctx(db.path());
  sim::SimSetup setup = sim::default_sim_setup("catamaran:m200");
  setup.vehicle.environment.current = {0.3, 315.0};
  const std::int64_t mission = avk::testing::run_recorded_mission(
      app::store_of(ctx), "m200", avk::testing::example_text("thesis-fig4-1.json"), setup);
  const auto stored = app::store_of(ctx).currents().for_mission(mission);
  ASSERT_TRUE(stored && stored->speed_reference);
  const auto r = app::estimate_mission_current(ctx, mission);
  ASSERT_TRUE(r && r->speed_reference && r->drift_scatter);
  const auto& e = *r->speed_reference;
  std::printf(
      "M200 in 0.3 m/s: %zu legs, rms over ground %.3f, through the water %.3f, separation %.3f "
      "m/s; drift scatter along %.3f cross %.3f m/s over %zu legs of %.1f s\n",
      e.legs, e.rms_over_ground_mps, e.rms_through_water_mps, e.separation_mps,
      r->drift_scatter->along_mps, r->drift_scatter->cross_mps, r->drift_scatter->legs,
      r->drift_scatter->mean_leg_s);
  EXPECT_EQ(e.identified, kin::SpeedReference::over_ground);
  EXPECT_EQ(stored->speed_reference->identified, kin::SpeedReference::over_ground);
  EXPECT_EQ(r->motion_legs, e.legs);
  EXPECT_GT(r->drift_scatter->mean_leg_s, app::kMotionLegMinS);

  const auto m = app::vehicle_motion(ctx, "m200");
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->speed_reference.value, kin::SpeedReference::over_ground);
  EXPECT_EQ(m->speed_reference.source, "identified");
  EXPECT_EQ(m->speed_reference.mission_id, mission);
  EXPECT_EQ(m->speed_reference.missions_over_ground, 1u);
  EXPECT_EQ(m->drift_scatter.source, "measured");
  ASSERT_TRUE(m->current);
  EXPECT_NEAR(m->current->estimate.speed_mps(), 0.3, 0.05);
}

// The same hull with its thrust mapped open loop from the commanded speed (66 % at 1 m/s makes
// about 1 m/s through the water) holds the speed through the water. One speed, so the open-loop
// map's curvature does not matter, and a ConditionSet that accepts the speed over ground the
// current makes of it.
TEST(VehicleMotion, AnOpenLoopThrustMapHoldsTheSpeedThroughTheWater) {
  avk::testing::TempDb db("avk_app_motion_tw");
  app::Context ctx(db.path());
  sim::SimSetup setup = sim::default_sim_setup("catamaran:m200");
  setup.vehicle.environment.current = {0.3, 60.0};
  setup.vehicle.pid.speed_factor = 66.0;
  const std::string mission_text = R"({
    "name": "one speed",
    "turn_array": {"speeds_mps": [1.0], "dheadings_deg": [10, 40, 70, 100, 130, 160],
                   "direction": "alternate", "repeats": 2},
    "condition_set": {"speed_tolerance_mps": 0.5, "max_yaw_rate_dps": 1.0, "window": 5},
    "constant_heading": {"completion_threshold_deg": 5},
    "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                         "buffer_m": 25, "return_point_m": [0, -70]}})";
  const std::int64_t mission =
      avk::testing::run_recorded_mission(app::store_of(ctx), "jet", mission_text, setup);
  const auto r = app::estimate_mission_current(ctx, mission);
  ASSERT_TRUE(r && r->speed_reference) << (r ? r->result.why_not : r.error().message);
  const auto& e = *r->speed_reference;
  std::printf(
      "open-loop thrust in 0.3 m/s: %zu legs, rms over ground %.3f, through the water "
      "%.3f, separation %.3f m/s\n",
      e.legs, e.rms_over_ground_mps, e.rms_through_water_mps, e.separation_mps);
  EXPECT_EQ(e.identified, kin::SpeedReference::through_water);
  const auto m = app::vehicle_motion(ctx, "jet");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->speed_reference.value, kin::SpeedReference::through_water);
}

store::StoredCurrent stored(std::int64_t mission, double east, double north,
                            std::optional<kin::SpeedReference> identified,
                            std::optional<kin::DriftScatter> scatter) {
  store::StoredCurrent c;
  c.mission_id = mission;
  c.estimate.east_mps = east;
  c.estimate.north_mps = north;
  c.estimate.covariance = {1e-5, 0.0, 1e-5};
  c.estimate.legs = 12;
  c.speed_reference = kin::SpeedReferenceEvidence{6, 0.02, 0.1, 0.08, identified};
  c.drift_scatter = scatter;
  return c;
}

TEST(VehicleMotion, TheNewestIdentificationWinsAndTheScatterIsPooled) {
  avk::testing::TempDb db("avk_app_motion_pool");
  app::Context ctx(db.path());
  store::Store& s = app::store_of(ctx);
  s.vehicles().upsert({"v", "usim", 2.0, 1.2});
  const auto a = s.missions().create("v", "a", "{}");
  const auto b = s.missions().create("v", "b", "{}");
  const auto c = s.missions().create("v", "c", "{}");
  const auto d = s.missions().create("v", "d", "{}");
  s.currents().save(
      stored(a, 0.2, 0.0, kin::SpeedReference::over_ground, kin::DriftScatter{0.1, 0.0, 1, 10.0}),
      {});
  s.currents().save(
      stored(b, 0.0, 0.2, kin::SpeedReference::through_water, kin::DriftScatter{0.0, 0.1, 3, 20.0}),
      {});
  s.currents().save(stored(c, 0.01, 0.0, std::nullopt, std::nullopt), {});
  // Not evaluated (stored before schema 12): counts for nothing.
  store::StoredCurrent old = stored(d, 0.0, 0.0, std::nullopt, std::nullopt);
  old.speed_reference.reset();
  s.currents().save(old, {});

  const auto m = app::vehicle_motion(ctx, "v");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->speed_reference.value, kin::SpeedReference::through_water);
  EXPECT_EQ(m->speed_reference.source, "identified");
  EXPECT_EQ(m->speed_reference.mission_id, b);
  EXPECT_EQ(m->speed_reference.missions_over_ground, 1u);
  EXPECT_EQ(m->speed_reference.missions_through_water, 1u);
  EXPECT_EQ(m->speed_reference.missions_undetermined, 1u);
  EXPECT_EQ(m->drift_scatter.source, "measured");
  EXPECT_EQ(m->drift_scatter.missions, 2u);
  EXPECT_EQ(m->drift_scatter.scatter.legs, 4u);
  EXPECT_NEAR(m->drift_scatter.scatter.along_mps, std::sqrt(0.01 / 4.0), 1e-12);
  EXPECT_NEAR(m->drift_scatter.scatter.cross_mps, std::sqrt(0.03 / 4.0), 1e-12);
  // The newest significant current: b's (c's 0.01 m/s is not told apart from still water).
  ASSERT_TRUE(m->current);
  EXPECT_EQ(m->current->mission_id, b);

  // Restricted to some missions (a held-out evaluation's table): only theirs count.
  const std::vector<std::int64_t> only_a{a, c};
  const auto ma = app::vehicle_motion(ctx, "v", only_a);
  ASSERT_TRUE(ma);
  EXPECT_EQ(ma->speed_reference.value, kin::SpeedReference::over_ground);
  EXPECT_EQ(ma->speed_reference.mission_id, a);
  EXPECT_EQ(ma->speed_reference.missions_through_water, 0u);
  EXPECT_EQ(ma->drift_scatter.missions, 1u);
  EXPECT_NEAR(ma->drift_scatter.scatter.along_mps, 0.1, 1e-12);
  ASSERT_TRUE(ma->current);
  EXPECT_EQ(ma->current->mission_id, a);
}

TEST(VehicleMotion, DefaultsUntilMeasuredAndUnknownVehiclesAreNotFound) {
  avk::testing::TempDb db("avk_app_motion_default");
  app::Context ctx(db.path());
  store::Store& s = app::store_of(ctx);
  EXPECT_EQ(app::vehicle_motion(ctx, "nobody").error().code, app::ErrorCode::not_found);
  s.vehicles().upsert({"v", "usim", 2.0, 1.2});
  auto m = app::vehicle_motion(ctx, "v");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->speed_reference.value, app::kDefaultSpeedReference);
  EXPECT_EQ(m->speed_reference.source, "default");
  EXPECT_FALSE(m->speed_reference.mission_id);
  EXPECT_FALSE(m->speed_reference.evidence);
  EXPECT_EQ(m->drift_scatter.source, "default");
  EXPECT_EQ(m->drift_scatter.scatter, app::kDefaultDriftScatter);
  EXPECT_FALSE(m->current);
  // An undetermined mission is shown as the evidence behind the default.
  const auto a = s.missions().create("v", "a", "{}");
  s.currents().save(stored(a, 0.01, 0.0, std::nullopt, std::nullopt), {});
  m = app::vehicle_motion(ctx, "v");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->speed_reference.source, "default");
  EXPECT_EQ(m->speed_reference.mission_id, a);
  ASSERT_TRUE(m->speed_reference.evidence);
  EXPECT_FALSE(m->speed_reference.evidence->identified);
}

}  // namespace
