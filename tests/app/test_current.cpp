// The current a mission flew in, from the steady legs before its turns: the thesis' Figure 4-1
// mission on the simulated M200 in a known uniform current, with GNSS and compass noise.
#include <gtest/gtest.h>

#include <cstdio>

#include "app/context.hpp"
#include "app/current.hpp"
#include "kinematics/angles.hpp"
#include "support/example_file.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

struct Case {
  double speed_mps;
  double toward_deg;
};

class MissionCurrentTest : public ::testing::TestWithParam<Case> {};

TEST_P(MissionCurrentTest, OneFigure41MissionFindsTheCurrentWithinTheAcceptance) {
  const Case c = GetParam();
  avk::testing::TempDb db("avk_app_current");
  app::Context ctx(db.path());
  sim::SimSetup setup = sim::default_sim_setup("catamaran:m200");
  setup.vehicle.environment.current = {c.speed_mps, c.toward_deg};
  const std::int64_t mission = avk::testing::run_recorded_mission(
      ctx.db(), "m200", avk::testing::example_text("thesis-fig4-1.json"), setup);
  const auto r = app::estimate_mission_current(ctx, mission);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GE(r->legs_used, 15u) << "of " << r->turns << " turns";
  ASSERT_TRUE(r->result.estimate) << r->result.why_not;
  const auto& e = *r->result.estimate;
  std::printf(
      "current %.2f m/s toward %.0f deg: estimated %.3f +- %.3f m/s toward %.1f +- %.1f deg "
      "from %zu legs (speed through water / commanded %.3f)\n",
      c.speed_mps, c.toward_deg, e.speed_mps(), e.speed_sd_mps(), e.toward_deg(), e.toward_sd_deg(),
      r->legs_used, e.speed_scale);
  // Issue 17: within 0.05 m/s and 15 deg of the truth after one Figure 4-1 mission.
  EXPECT_NEAR(e.speed_mps(), c.speed_mps, 0.05);
  EXPECT_LT(std::abs(kinematics::angle180_deg(e.toward_deg() - c.toward_deg)), 15.0)
      << e.toward_deg();
  EXPECT_GT(e.speed_sd_mps(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(KnownCurrents, MissionCurrentTest,
                         ::testing::Values(Case{0.1, 200.0}, Case{0.2, 60.0}, Case{0.3, 315.0}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           return std::to_string(static_cast<int>(i.param.speed_mps * 100.0)) +
                                  "cm_s_toward_" +
                                  std::to_string(static_cast<int>(i.param.toward_deg)) + "deg";
                         });

TEST(MissionCurrent, AnUnknownMissionIsNotFound) {
  avk::testing::TempDb db("avk_app_current_none");
  app::Context ctx(db.path());
  const auto r = app::estimate_mission_current(ctx, 42);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, app::ErrorCode::not_found);
}

TEST(MissionCurrent, StillWaterIsNearlyNoCurrent) {
  avk::testing::TempDb db("avk_app_current_calm");
  app::Context ctx(db.path());
  const std::int64_t mission = avk::testing::run_recorded_mission(
      ctx.db(), "m200", avk::testing::example_text("thesis-fig4-1.json"),
      sim::default_sim_setup("catamaran:m200"));
  const auto r = app::estimate_mission_current(ctx, mission);
  ASSERT_TRUE(r && r->result.estimate);
  EXPECT_LT(r->result.estimate->speed_mps(), 0.03);
}

}  // namespace
