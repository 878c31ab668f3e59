// The plans a mission follows: the turn plan and its resumption, the side an automatic-direction
// turn takes, and persistent excitation's seeded random steps and return.
#include <gtest/gtest.h>

#include "mission/mission_sim.hpp"

using namespace avk::testing::mission_sim;

namespace {

MissionConfig excitation_config(std::uint64_t seed) {
  MissionConfig c;
  c.name = "pe";
  c.kind = MissionKind::persistent_excitation;
  c.region = square_region(200, 20);
  // 1 m/s for 60 s, steps of 20..60 deg every 3..6 s.
  c.excitation = ExcitationConfig{1.0, 60.0, 20.0, 60.0, 3.0, 6.0, seed};
  return c;
}

}  // namespace

// ---- 10. Direction auto ---------------------------------------------------------------------

TEST(DirectionAuto, TurnsAwayFromANearBoundary) {
  const Container c(square_region(100, 10));
  // 15 m from the east boundary heading north: a right turn's 10 m run-out ends 5 m from it.
  const SideChoice near = choose_side(c, {85, 0, 0}, 1.0, 90, nullptr, TurnSide::right);
  EXPECT_EQ(near.side, TurnSide::left);
  EXPECT_FALSE(near.from_table);
  EXPECT_NEAR(near.right_clearance_m, 5.0, 1e-6);
  EXPECT_NEAR(near.left_clearance_m, 15.0, 1e-6);
  // Both clear: the preferred side.
  EXPECT_EQ(choose_side(c, {0, 0, 0}, 1.0, 90, nullptr, TurnSide::right).side, TurnSide::right);
  EXPECT_EQ(choose_side(c, {0, 0, 0}, 1.0, 90, nullptr, TurnSide::left).side, TurnSide::left);
  // Near the west boundary heading north the mirror image holds.
  EXPECT_EQ(choose_side(c, {-85, 0, 0}, 1.0, 90, nullptr, TurnSide::left).side, TurnSide::right);
}

// Signed goals of the turns of an automatic-direction mission started at (x, y) heading north.
std::vector<double> auto_goals(double x, double y, int repeats) {
  MissionConfig c = turns_config({1.0}, {90}, DirectionPolicy::automatic, square_region(100, 10));
  c.turn_array.repeats = repeats;
  Sim r(c, FakeVehicle(x, y, 0, 1.0));
  EXPECT_TRUE(r.finish());
  EXPECT_EQ(r.runner.state(), MissionState::done);
  std::vector<double> goals;
  for (const auto& t : r.rec.turns) {
    EXPECT_EQ(t.status, TurnStatus::ok);
    EXPECT_FALSE(t.task.side.has_value());
    goals.push_back(t.raw.meta().goal_dheading_deg);
  }
  return goals;
}

TEST(DirectionAuto, RunnerTurnsAwayFromTheBoundaryElseAlternates) {
  EXPECT_EQ(auto_goals(85, -50, 1), std::vector<double>{-90.0});  // away from x = 100
  // With room on both sides: right first, then the side not taken last time.
  EXPECT_EQ(auto_goals(0, -50, 3), (std::vector<double>{90.0, -90.0, 90.0}));
}

// ---- 11. Persistent excitation --------------------------------------------------------------

namespace {
struct Excitation {
  std::vector<std::pair<double, double>> steps;  // (t, desired heading) each time it changes
  std::vector<HelmMode> modes;
  double exciting_s = -1.0;  // from entering EXCITING to RETURNING
};
Excitation excite(std::uint64_t seed) {
  Sim r(excitation_config(seed), FakeVehicle(0, 0, 0, 1.0));
  Excitation out;
  const Hook watch = [&](double t) {
    const auto d = r.runner.desired_heading_deg();
    if (r.runner.mode() == HelmMode::exciting && d &&
        (out.steps.empty() || out.steps.back().second != *d))
      out.steps.emplace_back(t, *d);
  };
  EXPECT_TRUE(r.finish(300, watch));
  EXPECT_EQ(r.runner.state(), MissionState::done);
  out.modes = r.rec.mode_path();
  if (r.rec.modes.size() >= 2) out.exciting_s = r.rec.modes[1].t_s - r.rec.modes[0].t_s;
  return out;
}
}  // namespace

TEST(PersistentExcitation, SeededRandomStepsThenReturn) {
  const Excitation a = excite(7);
  using M = HelmMode;
  EXPECT_EQ(a.modes, (std::vector<M>{M::containing, M::exciting, M::returning, M::done}));
  EXPECT_NEAR(a.exciting_s, 60.0, 0.3);
  const ExcitationConfig e = *excitation_config(7).excitation;
  ASSERT_GE(a.steps.size(), 60.0 / e.max_interval_s - 1);
  for (std::size_t i = 1; i < a.steps.size(); ++i) {
    const auto [t0, h0] = a.steps[i - 1];
    const auto [t1, h1] = a.steps[i];
    EXPECT_GE(std::abs(k::angle180_deg(h1 - h0)), e.min_step_deg - 1e-9);
    EXPECT_LE(std::abs(k::angle180_deg(h1 - h0)), e.max_step_deg + 1e-9);
    EXPECT_GE(t1 - t0, e.min_interval_s - 1e-9);
    EXPECT_LE(t1 - t0, e.max_interval_s + 0.2 + 1e-9);  // steps happen at the helm's 5 Hz ticks
  }
  const auto turns_right = [](const auto& p, const auto& q) {
    return k::angle180_deg(q.second - p.second) > 0.0;
  };
  const auto right = std::adjacent_find(a.steps.begin(), a.steps.end(), turns_right);
  const auto left = std::adjacent_find(a.steps.begin(), a.steps.end(), std::not_fn(turns_right));
  EXPECT_TRUE(right != a.steps.end() && left != a.steps.end());  // steps of both signs
  EXPECT_EQ(excite(7).steps, a.steps);
  EXPECT_NE(excite(8).steps, a.steps);
}

TEST(MissionRunner, ReturnPointReachedBySlippingPastIt) {
  MissionConfig c = excitation_config(1);
  c.excitation->duration_s = 0.0;  // straight to RETURNING
  c.region.return_point = {6, 20};
  Sim r(c, FakeVehicle(0, 0, 0, 1.0));
  r.vehicle.yaw_rate_dps = 0.0;  // goes straight on, passing 6 m from the return point
  ASSERT_TRUE(r.finish(100));
  EXPECT_EQ(r.runner.state(), MissionState::done);
  const double d = k::distance_m({r.rec.navs.back().nav.x_m, r.rec.navs.back().nav.y_m}, {6, 20});
  EXPECT_GT(d, c.region.capture_radius_m);  // never within the capture radius
  EXPECT_LE(d, 3.0 * c.region.capture_radius_m);
}

// ---- 12. Plan ---------------------------------------------------------------------------------

TEST(TurnPlan, SpeedMajorAlternatingByIndexAndResumable) {
  MissionConfig c =
      turns_config({0.5, 1.0}, {30, 90}, DirectionPolicy::alternate, square_region(100, 10));
  c.turn_array.repeats = 2;
  const auto plan = plan_turns(c);
  ASSERT_EQ(plan.size(), 8u);
  const double speeds[] = {0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0};
  const double dheadings[] = {30, 30, 90, 90, 30, 30, 90, 90};
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].index, i);
    EXPECT_EQ(plan[i].speed_mps, speeds[i]);
    EXPECT_EQ(plan[i].dheading_deg, dheadings[i]);
    EXPECT_EQ(plan[i].side, i % 2 == 0 ? TurnSide::right : TurnSide::left);
    EXPECT_EQ(plan[i].attempts, 0);
  }
  const auto left = remaining_turns(plan, {{0.5, 30, 1, std::nullopt}, {1.0, 90, 2, std::nullopt}});
  std::vector<std::size_t> indices;
  for (const auto& t : left) {
    indices.push_back(t.index);
    EXPECT_EQ(t.side, plan[t.index].side);  // the side of the original plan
  }
  EXPECT_EQ(indices, (std::vector<std::size_t>{1, 2, 3, 4, 5}));
  // A runner resumed with what is left counts the turns already done.
  FakeVehicle v(0, 0, 0);
  MissionRunner runner(c, v, left, {});
  ASSERT_EQ(runner.cells().size(), 4u);
  EXPECT_EQ(runner.cells()[0].ok, 1);
  EXPECT_EQ(runner.cells()[1].ok, 0);
  EXPECT_EQ(runner.cells()[3].ok, 2);
  EXPECT_EQ(runner.cells()[3].planned, 2);

  c.turn_array.direction = DirectionPolicy::automatic;
  for (const auto& t : plan_turns(c))
    EXPECT_FALSE(t.side.has_value());
  c.turn_array.direction = DirectionPolicy::left;
  EXPECT_EQ(plan_turns(c)[0].side, TurnSide::left);
  EXPECT_TRUE(plan_turns(excitation_config(1)).empty());
}

TEST(TurnPlan, InitialYawRatesAreAnAxisBetweenHeadingChangeAndRepeats) {
  MissionConfig c = turns_config({1.0}, {30, 90}, DirectionPolicy::right, square_region(100, 10));
  c.turn_array.repeats = 2;
  c.turn_array.initial_yaw_rates_dps = {-8.0, 0.0, 8.0};
  const auto plan = plan_turns(c);
  ASSERT_EQ(plan.size(), 12u);
  const double rates[] = {-8, -8, 0, 0, 8, 8};
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].dheading_deg, i < 6 ? 30.0 : 90.0);
    EXPECT_EQ(plan[i].initial_yaw_rate_dps, rates[i % 6]) << i;
  }
  c.turn_array.initial_yaw_rates_dps.clear();
  for (const auto& t : plan_turns(c))
    EXPECT_EQ(t.initial_yaw_rate_dps, 0.0);
}
