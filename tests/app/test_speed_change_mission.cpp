// On the simulated M200: turns with a commanded speed change (u0 -> u1),
// collected by a mission and compared with the vehicle's known speed response.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_vehicle.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

constexpr const char* kSpeedChangeMission = R"({
  "name": "speed-change",
  "turn_array": {"dheadings_deg": [90], "repeats": 2,
                 "speed_changes": [{"from_mps": 1.5, "to_mps": 0.75}]},
  "operating_region": {"polygon_m": [[-150,-150],[150,-150],[150,150],[-150,150]],
                       "buffer_m": 25, "return_point_m": [0, -100]}})";

// The simulated M200's speed on a straight course after its commanded speed steps from u0 to u1
// at t = 0 (sampled at 10 Hz from the plant's truth): the known response the recorded turns are
// compared with.
struct SpeedResponse {
  double dt_s = 0.1;
  std::vector<double> speed_mps;
  double at(double t_s) const {
    const double k = std::clamp(t_s / dt_s, 0.0, static_cast<double>(speed_mps.size() - 1));
    const std::size_t i = static_cast<std::size_t>(std::floor(k));
    const std::size_t j = std::min(i + 1, speed_mps.size() - 1);
    return speed_mps[i] + (k - static_cast<double>(i)) * (speed_mps[j] - speed_mps[i]);
  }
};

SpeedResponse straight_speed_step(double u0, double u1) {
  sim::Scheduler s;
  sim::SimVehicle v(sim::sim_vehicle_defaults("catamaran:m200"), s);
  double speed = u0;
  s.add("helm", 4.0, [&](double now) { v.command({now, 0.0, speed}); });
  s.run_until(60.0);
  speed = u1;
  SpeedResponse r;
  for (int k = 0; k <= 300; ++k) {
    s.run_until(60.0 + 0.1 * k);
    r.speed_mps.push_back(v.truth().speed_over_ground_mps);
  }
  return r;
}

}  // namespace

TEST(SpeedChangeMission, TurnsSlowFromU0TowardsU1AsTheVehicleDoesOnAStraightCourse) {
  avk::testing::TempDb db("avk_app_speed_change");
  app::Context ctx(db.path());
  const std::int64_t mission = avk::testing::run_recorded_mission(
      app::store_of(ctx), "m200", kSpeedChangeMission, sim::default_sim_setup("catamaran:m200"));
  const auto turns = app::store_of(ctx).turns().load_normalized({mission}, std::string("m200"));
  ASSERT_EQ(turns.size(), 2u);
  const SpeedResponse straight = straight_speed_step(1.5, 0.75);
  for (const auto& t : turns) {
    const auto& m = t.meta();
    ASSERT_TRUE(m.speed_after_mps);
    EXPECT_EQ(*m.speed_after_mps, 0.75);
    EXPECT_EQ(m.commanded_speed_mps, 1.5);
    const auto& s = t.samples();
    ASSERT_GE(s.size(), 10u);
    const double t0 = s.front().t_s;
    EXPECT_NEAR(s.front().speed_mps, 1.5, 0.1);
    // The speed falls during the turn: well below u0 at completion, not yet below u1.
    EXPECT_LT(s.back().speed_mps, 1.5 - 0.2) << "after " << s.back().t_s - t0 << " s";
    EXPECT_GT(s.back().speed_mps, 0.75 - 0.1);
    // It follows the straight-course response to within what the turn itself costs (a speed
    // sag early in the turn): the same fall, in the same time.
    double sum_diff = 0.0, max_abs = 0.0;
    for (const auto& p : s) {
      const double d = p.speed_mps - straight.at(p.t_s - t0);
      sum_diff += d;
      max_abs = std::max(max_abs, std::abs(d));
    }
    const double mean_diff = sum_diff / static_cast<double>(s.size());
    EXPECT_NEAR(s.back().speed_mps, straight.at(s.back().t_s - t0), 0.15);
    std::printf(
        "turn %.0f deg in %.1f s: speed %.2f -> %.2f m/s; straight response %.2f at the "
        "end; mean difference %.3f, max %.3f m/s\n",
        m.observed_dheading_deg, s.back().t_s - t0, s.front().speed_mps, s.back().speed_mps,
        straight.at(s.back().t_s - t0), mean_diff, max_abs);
    EXPECT_LT(max_abs, 0.3);
    EXPECT_LT(std::abs(mean_diff), 0.15);
  }
  // The mission's cells keep the speed change apart from constant-speed cells.
  const auto stats = app::store_of(ctx).missions().cell_stats(mission);
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].speed_after_mps, 0.75);
  EXPECT_EQ(stats[0].n_ok, 2);
}
