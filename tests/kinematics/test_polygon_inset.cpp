// The buffer line of an operating region: analytic insets of rectangles and regular polygons,
// either winding, invariant under rotation and translation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinematics/polygon_inset.hpp"

namespace {

using avk::kinematics::inset_polygon;
using avk::kinematics::Point;
using avk::kinematics::Polyline;

Polyline square(double half) {
  return {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
}

TEST(PolygonInset, ASquareShrinksByTheDistanceOnEverySide) {
  const auto in = inset_polygon(square(80.0), 12.0);
  ASSERT_EQ(in.size(), 4u);
  for (const auto& p : in) {
    EXPECT_NEAR(std::abs(p.x_m), 68.0, 1e-9);
    EXPECT_NEAR(std::abs(p.y_m), 68.0, 1e-9);
  }
}

TEST(PolygonInset, WindingDoesNotMatter) {
  Polyline cw = square(50.0);
  std::reverse(cw.begin(), cw.end());
  const auto in = inset_polygon(cw, 5.0);
  ASSERT_EQ(in.size(), 4u);
  for (const auto& p : in)
    EXPECT_NEAR(std::max(std::abs(p.x_m), std::abs(p.y_m)), 45.0, 1e-9);
}

TEST(PolygonInset, ARegularPolygonKeepsItsCentreAndLosesTheDistanceFromItsApothem) {
  const int n = 7;
  const double r = 40.0;  // circumradius
  const double apothem = r * std::cos(std::numbers::pi / n);
  const double d = 6.0;
  Polyline poly;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n + 0.3;
    poly.push_back({12.0 + r * std::cos(a), -7.0 + r * std::sin(a)});
  }
  const auto in = inset_polygon(poly, d);
  ASSERT_EQ(in.size(), static_cast<std::size_t>(n));
  // The inset of a regular polygon is the similar polygon with apothem - d.
  const double r_in = (apothem - d) / std::cos(std::numbers::pi / n);
  for (const auto& p : in)
    EXPECT_NEAR(std::hypot(p.x_m - 12.0, p.y_m + 7.0), r_in, 1e-9);
}

TEST(PolygonInset, AClosingVertexAndCollinearVerticesAreHarmless) {
  Polyline poly = {{0, 0}, {50, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 0}};
  const auto in = inset_polygon(poly, 10.0);
  ASSERT_EQ(in.size(), 5u);
  for (const auto& p : in) {
    EXPECT_GE(p.x_m, 10.0 - 1e-9);
    EXPECT_LE(p.x_m, 90.0 + 1e-9);
    EXPECT_NEAR(std::min({p.y_m - 10.0, 90.0 - p.y_m, p.x_m - 10.0, 90.0 - p.x_m}), 0.0, 1e-9);
  }
}

TEST(PolygonInset, TooWideOrDegenerateGivesNothing) {
  EXPECT_TRUE(inset_polygon(square(10.0), 11.0).empty());
  EXPECT_TRUE(inset_polygon({{0, 0}, {1, 1}}, 0.1).empty());
  EXPECT_TRUE(inset_polygon({{0, 0}, {1, 0}, {2, 0}}, 0.1).empty());
}

}  // namespace
