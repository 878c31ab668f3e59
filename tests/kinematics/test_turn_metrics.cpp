#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/mean_turn.hpp"
#include "kinematics/turn_metrics.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

XGridCurve curve(double x0_m, double step_m, std::vector<double> y_m) {
  XGridCurve c;
  c.x0_m = x0_m;
  c.step_m = step_m;
  c.y_m = std::move(y_m);
  return c;
}

Polyline noisy_arc(double dheading_deg, double radius_m, unsigned seed) {
  ArcTurnSpec spec;
  spec.dheading_deg = dheading_deg;
  spec.lead_in_m = 2.0;
  spec.radius_m = radius_m;
  spec.tail_m = 3.0;
  spec.position_noise_m = 0.05;
  spec.seed = seed;
  return make_arc_turn(spec).normalized().points();
}

}  // namespace

TEST(TurnMetrics, MseOfCurvesByHand) {
  const XGridCurve a = curve(0.0, 0.5, {1.0, 2.0, 3.0});
  const XGridCurve b = curve(0.0, 0.5, {2.0, 4.0, 3.0});
  EXPECT_DOUBLE_EQ(mse_m2(a, b), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(mse_m2(b, a), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(mse_m2(a, a), 0.0);
  // Only the common x domain counts: b2 covers x = 0.5..1.5, overlapping a at 0.5 and 1.0.
  const XGridCurve b2 = curve(0.5, 0.5, {4.0, 5.0, 100.0});
  EXPECT_DOUBLE_EQ(mse_m2(a, b2), (4.0 + 4.0) / 2.0);
  EXPECT_DOUBLE_EQ(mse_m2(b2, a), (4.0 + 4.0) / 2.0);
}

TEST(TurnMetrics, MseRejectsIncomparableCurves) {
  const XGridCurve a = curve(0.0, 0.5, {1.0, 2.0, 3.0});
  EXPECT_THROW(mse_m2(a, curve(0.0, 0.25, {1.0})), std::invalid_argument);
  EXPECT_THROW(mse_m2(a, curve(0.25, 0.5, {1.0})), std::invalid_argument);
  EXPECT_THROW(mse_m2(a, curve(5.0, 0.5, {1.0})), std::invalid_argument);
  EXPECT_THROW(mse_m2(a, XGridCurve{}), std::invalid_argument);
}

TEST(TurnMetrics, MseOfTurnsIsSymmetricAndZeroForIdentical) {
  const Polyline a = noisy_arc(70.0, 3.0, 1);
  const Polyline b = noisy_arc(70.0, 4.0, 2);
  EXPECT_DOUBLE_EQ(mse_m2(a, a, 70.0), 0.0);
  EXPECT_GT(mse_m2(a, b, 70.0), 0.0);
  EXPECT_DOUBLE_EQ(mse_m2(a, b, 70.0), mse_m2(b, a, 70.0));
  // Two turns alone are compared on the same domain their mean uses.
  const CellErrors e = cell_errors({a, b}, 70.0);
  const XGridCurve ca = resample_on_x_grid(a, 70.0, e.mean.x_end_m(), 0.01);
  const XGridCurve cb = resample_on_x_grid(b, 70.0, e.mean.x_end_m(), 0.01);
  EXPECT_NEAR(mse_m2(a, b, 70.0), mse_m2(ca, cb), 1e-12);
  // With equal weights each turn is half the pair's difference from the mean.
  EXPECT_NEAR(e.per_turn_mse_m2[0], mse_m2(a, b, 70.0) / 4.0, 1e-12);
}

TEST(TurnMetrics, InstantaneousTurnIsTheGoalRay) {
  const XGridCurve r45 = instantaneous_turn(45.0, 2.0, 0.5);
  ASSERT_EQ(r45.y_m.size(), 5u);
  for (std::size_t k = 0; k < r45.y_m.size(); ++k)
    EXPECT_NEAR(r45.y_m[k], r45.x_at_m(k), 1e-12);
  const XGridCurve r135 = instantaneous_turn(-135.0, 2.0, 0.5);
  for (std::size_t k = 0; k < r135.y_m.size(); ++k)
    EXPECT_NEAR(r135.y_m[k], -r135.x_at_m(k), 1e-12);
  const XGridCurve r90 = instantaneous_turn(90.0, 2.0, 0.5);
  for (double y : r90.y_m)
    EXPECT_NEAR(y, 0.0, 1e-12);
  const XGridCurve r30 = instantaneous_turn(30.0, 1.0, 0.01);
  EXPECT_NEAR(r30.y_m.back(), std::sqrt(3.0), 1e-12);
  EXPECT_EQ(instantaneous_turn(180.0, 2.0, 0.5).y_m, std::vector<double>{0.0});
}

TEST(TurnMetrics, InstantaneousErrorByHand) {
  // A lead-in of L, then an instant turn to the goal: against the goal ray from the origin the
  // error is L at every grid x except x = 0 (first crossing at the start: no error).
  const double lead_m = 3.0, x_m = 10.0;
  for (double goal_deg : {45.0, 90.0, 120.0}) {
    const double cot = 1.0 / std::tan(deg_to_rad(goal_deg));
    const Polyline turn{{0, 0}, {0, lead_m}, {x_m, lead_m + x_m * cot}};
    const CellErrors e = cell_errors({turn}, goal_deg);
    ASSERT_EQ(e.mean.y_m.size(), 1001u);
    EXPECT_NEAR(e.instantaneous_mse_m2, lead_m * lead_m * 1000.0 / 1001.0, 1e-9) << goal_deg;
    EXPECT_NEAR(e.avk_error_m2, 0.0, 1e-20);
  }
}

TEST(TurnMetrics, AvkErrorIsTheMeanOfPerTurnErrors) {
  std::vector<Polyline> turns;
  for (unsigned seed = 1; seed <= 5; ++seed)
    turns.push_back(noisy_arc(-110.0, 2.5 + 0.3 * seed, seed));
  const CellErrors e = cell_errors(turns, -110.0);
  ASSERT_EQ(e.per_turn_mse_m2.size(), turns.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < turns.size(); ++i) {
    const XGridCurve c = resample_on_x_grid(turns[i], -110.0, e.mean.x_end_m(), 0.01);
    EXPECT_NEAR(e.per_turn_mse_m2[i], mse_m2(c, e.mean), 1e-12);
    sum += e.per_turn_mse_m2[i];
  }
  EXPECT_NEAR(e.avk_error_m2, sum / 5.0, 1e-12);
  EXPECT_NEAR(e.instantaneous_mse_m2, mse_m2(instantaneous_turn(-110.0, e.mean.x_end_m()), e.mean),
              1e-12);
}

TEST(TurnMetrics, ObservedTurnsBeatTheInstantaneousAssumption) {
  // The thesis ordering (Figure 5-7: 0.23 m2 AVK against 16.8 m2 instantaneous for 70 deg).
  for (double goal_deg : {30.0, 70.0, 130.0, 170.0}) {
    std::vector<Polyline> turns;
    for (unsigned seed = 1; seed <= 6; ++seed)
      turns.push_back(noisy_arc(goal_deg, 3.0 + 0.2 * (seed % 3), seed));
    const CellErrors e = cell_errors(turns, goal_deg);
    EXPECT_LT(10.0 * e.avk_error_m2, e.instantaneous_mse_m2) << goal_deg;
  }
}
