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

Polyline arc_polyline(double dheading_deg, double lead_in_m, double radius_m, double dt_s = 0.05) {
  ArcTurnSpec spec;
  spec.dheading_deg = dheading_deg;
  spec.lead_in_m = lead_in_m;
  spec.radius_m = radius_m;
  spec.dt_s = dt_s;
  return make_arc_turn(spec).normalized().points();
}

Polyline shifted_y(Polyline line, double dy_m) {
  for (auto& p : line)
    p.y_m += dy_m;
  return line;
}

}  // namespace

TEST(MeanTurn, XGridCurveBasics) {
  XGridCurve c;
  EXPECT_TRUE(c.empty());
  EXPECT_DOUBLE_EQ(c.x_end_m(), 0.0);
  c.x0_m = 1.0;
  c.step_m = 0.5;
  c.y_m = {3.0, 4.0, 5.0};
  EXPECT_FALSE(c.empty());
  EXPECT_DOUBLE_EQ(c.x_end_m(), 2.0);
  const Polyline p = c.points();
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[1], (Point{1.5, 4.0}));
  EXPECT_EQ(x_grid_size(1.0, 0.01), 101u);
  EXPECT_EQ(x_grid_size(0.0, 0.01), 1u);
  EXPECT_EQ(x_grid_size(0.30000000000000004 - 1e-15, 0.1), 4u);  // rounding keeps the end
}

TEST(MeanTurn, MeanOfIdenticalTurnsIsTheTurn) {
  const Polyline turn = arc_polyline(70.0, 2.0, 3.0);
  const XGridCurve one = resample_on_x_grid(turn, 70.0, max_x_m(turn), 0.01);
  const CellErrors e = cell_errors({turn, turn, turn}, 70.0);
  ASSERT_EQ(e.mean.y_m.size(), one.y_m.size());
  for (std::size_t k = 0; k < one.y_m.size(); ++k)
    ASSERT_NEAR(e.mean.y_m[k], one.y_m[k], 1e-12) << k;
  ASSERT_EQ(e.per_turn_mse_m2.size(), 3u);
  EXPECT_NEAR(e.avk_error_m2, 0.0, 1e-20);
}

TEST(MeanTurn, ResampledArcFollowsTheCircle) {
  const double lead_m = 2.0, radius_m = 3.0;
  const Polyline turn = arc_polyline(90.0, lead_m, radius_m, 0.02);
  const XGridCurve c = resample_on_x_grid(turn, 90.0, radius_m, 0.01);
  ASSERT_EQ(c.y_m.size(), 301u);
  EXPECT_DOUBLE_EQ(c.y_m[0], 0.0);  // x = 0 is first crossed at the start
  for (std::size_t k = 1; k < c.y_m.size(); ++k) {
    const double x = c.x_at_m(k);
    const double y = lead_m + std::sqrt(radius_m * radius_m - (radius_m - x) * (radius_m - x));
    // Near x = R the circle is flat in y; near x = 0 it is steep, so chord error shows in y there.
    ASSERT_NEAR(c.y_m[k], y, 2e-3) << x;
  }
}

TEST(MeanTurn, LeadInIsReadAtTheFirstCrossing) {
  const double lead_m = 4.0, radius_m = 3.0;
  const XGridCurve c =
      resample_on_x_grid(arc_polyline(90.0, lead_m, radius_m, 0.02), 90.0, 1.0, 0.01);
  EXPECT_DOUBLE_EQ(c.y_m[0], 0.0);
  // Just right of x = 0 the path is past the whole lead-in.
  EXPECT_NEAR(c.y_m[1], lead_m + std::sqrt(2.0 * radius_m * 0.01 - 1e-4), 2e-3);
}

TEST(MeanTurn, CurlingPathUsesTheFirstCrossing) {
  // Out to x = 2, back to x = 1 higher up, then on to x = 3: x in (1, 2] is crossed first on the
  // way out, x in (2, 3] only after the curl.
  const Polyline curl{{0, 0}, {2, 2}, {1, 5}, {3, 7}};
  const XGridCurve c = resample_on_x_grid(curl, 45.0, 3.0, 0.5);
  ASSERT_EQ(c.y_m.size(), 7u);
  const std::vector<double> expected{0.0, 0.5, 1.0, 1.5, 2.0, 6.5, 7.0};
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(c.y_m[k], expected[k], 1e-12) << k;
}

TEST(MeanTurn, NegativeXNoiseAtTheStartIsIgnored) {
  const Polyline clean{{0, 0}, {0, 1.5}, {1, 2.5}, {2, 3.0}};
  const Polyline noisy{{0, 0}, {-0.02, 0.5}, {-0.01, 1.0}, {0, 1.5}, {1, 2.5}, {2, 3.0}};
  const XGridCurve a = resample_on_x_grid(clean, 60.0, 2.0, 0.01);
  const XGridCurve b = resample_on_x_grid(noisy, 60.0, 2.0, 0.01);
  ASSERT_EQ(a.y_m.size(), b.y_m.size());
  for (std::size_t k = 0; k < a.y_m.size(); ++k)
    ASSERT_NEAR(a.y_m[k], b.y_m[k], 1e-12) << k;
  // A turn that never gets right of x = 0 still has y(0) and is extended from its last point.
  const Polyline only_left{{0, 0}, {-0.1, 1.0}};
  const XGridCurve c = resample_on_x_grid(only_left, 45.0, 1.0, 0.5);
  ASSERT_EQ(c.y_m.size(), 3u);
  EXPECT_DOUBLE_EQ(c.y_m[0], 0.0);
  EXPECT_NEAR(c.y_m[2], 1.0 + 1.1, 1e-12);
}

TEST(MeanTurn, ExtensionAlongTheGoalHeadingIsARay) {
  const double goal_deg = 70.0;
  const Polyline small = arc_polyline(goal_deg, 2.0, 2.0);
  const Polyline big = arc_polyline(goal_deg, 2.0, 5.0);
  const double x_max = set_x_max_m({small, big}, goal_deg);
  EXPECT_DOUBLE_EQ(x_max, max_x_m(big));
  const XGridCurve c = resample_on_x_grid(small, goal_deg, x_max, 0.01);
  ASSERT_EQ(c.y_m.size(), x_grid_size(x_max, 0.01));
  const Point end = small.back();
  const double cot = 1.0 / std::tan(deg_to_rad(goal_deg));
  int extended = 0;
  for (std::size_t k = 0; k < c.y_m.size(); ++k) {
    if (c.x_at_m(k) <= end.x_m) continue;
    ASSERT_NEAR(c.y_m[k], end.y_m + (c.x_at_m(k) - end.x_m) * cot, 1e-12);
    ++extended;
  }
  EXPECT_GT(extended, 100);
}

TEST(MeanTurn, TurnsOffsetByPlusMinusDAverageToTheMiddle) {
  const double d_m = 0.4;
  const Polyline base = arc_polyline(50.0, 1.5, 4.0);
  const CellErrors e = cell_errors({shifted_y(base, d_m), shifted_y(base, -d_m)}, 50.0);
  const XGridCurve middle = resample_on_x_grid(base, 50.0, max_x_m(base), 0.01);
  ASSERT_EQ(e.mean.y_m.size(), middle.y_m.size());
  for (std::size_t k = 0; k < middle.y_m.size(); ++k)
    ASSERT_NEAR(e.mean.y_m[k], middle.y_m[k], 1e-12) << k;
  ASSERT_EQ(e.per_turn_mse_m2.size(), 2u);
  EXPECT_NEAR(e.per_turn_mse_m2[0], d_m * d_m, 1e-12);
  EXPECT_NEAR(e.per_turn_mse_m2[1], d_m * d_m, 1e-12);
  EXPECT_NEAR(e.avk_error_m2, d_m * d_m, 1e-12);
}

TEST(MeanTurn, MarginExtendsTheDomain) {
  const Polyline a = arc_polyline(90.0, 2.0, 3.0);
  const XGridCurve plain = mean_turn({a}, 90.0);
  const XGridCurve wide = mean_turn({a}, 90.0, {0.01, 1.5});
  EXPECT_NEAR(plain.x_end_m(), max_x_m(a), 0.01);
  EXPECT_NEAR(wide.x_end_m(), max_x_m(a) + 1.5, 0.01);
  // 90 degrees: the extension is level at the final y.
  EXPECT_NEAR(wide.y_m.back(), a.back().y_m, 1e-9);
}

TEST(MeanTurn, HalfTurnsAreAveragedOnTheirCommonXDomain) {
  EXPECT_TRUE(goal_ray_extends_in_x(170.0));
  EXPECT_TRUE(goal_ray_extends_in_x(-170.0));
  EXPECT_FALSE(goal_ray_extends_in_x(176.0));
  EXPECT_FALSE(goal_ray_extends_in_x(180.0));
  EXPECT_FALSE(goal_ray_extends_in_x(0.0));

  const double lead_m = 1.0;
  const Polyline r2 = arc_polyline(180.0, lead_m, 2.0, 0.02);
  const Polyline r3 = arc_polyline(180.0, lead_m, 3.0, 0.02);
  const XGridCurve mean = mean_turn({r2, r3}, 180.0);
  EXPECT_NEAR(mean.x_end_m(), 4.0, 0.011);  // 2 * the smaller radius
  // Each half circle read as y(x) at its first crossing is its upper half.
  for (std::size_t k = 1; k < mean.y_m.size(); k += 25) {
    const double x = mean.x_at_m(k);
    const double y2 = lead_m + std::sqrt(4.0 - (x - 2.0) * (x - 2.0));
    const double y3 = lead_m + std::sqrt(9.0 - (x - 3.0) * (x - 3.0));
    EXPECT_NEAR(mean.y_m[k], 0.5 * (y2 + y3), 5e-3) << x;
  }
  // Not extended even when a margin is asked for.
  EXPECT_EQ(mean_turn({r2, r3}, 180.0, {0.01, 2.0}).y_m.size(), mean.y_m.size());
  const XGridCurve alone = resample_on_x_grid(r3, 180.0, 10.0, 0.01);
  EXPECT_NEAR(alone.x_end_m(), 6.0, 0.011);  // stops at its own largest x

  const CellErrors e = cell_errors({r2, r3}, -180.0);
  EXPECT_TRUE(std::isfinite(e.avk_error_m2));
  EXPECT_GT(e.avk_error_m2, 0.0);
  EXPECT_TRUE(std::isnan(e.instantaneous_mse_m2));
}

TEST(MeanTurn, RejectsBadInput) {
  const Polyline ok{{0, 0}, {0, 1}, {1, 2}};
  EXPECT_THROW(mean_turn({}, 90.0), std::invalid_argument);
  EXPECT_THROW(mean_turn({ok, Polyline{{0, 0}}}, 90.0), std::invalid_argument);
  EXPECT_THROW(mean_turn({ok, Polyline{}}, 90.0), std::invalid_argument);
  EXPECT_THROW(mean_turn({ok}, 90.0, {0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(mean_turn({ok}, 90.0, {0.01, -1.0}), std::invalid_argument);
  EXPECT_THROW(resample_on_x_grid(Polyline{{0, 0}}, 90.0, 1.0, 0.01), std::invalid_argument);
  EXPECT_THROW(resample_on_x_grid(ok, 90.0, -1.0, 0.01), std::invalid_argument);
  EXPECT_THROW(resample_on_x_grid(ok, 90.0, 1e9, 0.01), std::invalid_argument);
  EXPECT_THROW(resample_on_x_grid(Polyline{{0, 0}, {NAN, 1}}, 90.0, 1.0, 0.01),
               std::invalid_argument);
  EXPECT_THROW(cell_errors({}, 90.0), std::invalid_argument);
}
