#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"
#include "kinematics/curve_fit.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/simplify.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::circular_arc;
using avk::testing::make_arc_turn;

namespace {

bool contains(const Polyline& line, Point p) {
  for (const Point& q : line)
    if (q == p) return true;
  return false;
}

}  // namespace

TEST(Simplify, StraightLineCollapsesToItsEnds) {
  Polyline line;
  for (int i = 0; i <= 1000; ++i)
    line.push_back({0.3 * i, -0.1 * i});
  const Polyline s = simplify_polyline(line, 1e-9);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.front(), line.front());
  EXPECT_EQ(s.back(), line.back());
}

TEST(Simplify, ZigZagKeepsItsCorners) {
  // Corners 1 m off the axis, 10 dense points on each leg.
  Polyline dense;
  const Point corners[] = {{0, 0}, {2, 1}, {4, -1}, {6, 1}, {8, 0}};
  for (int c = 0; c + 1 < 5; ++c) {
    for (int k = 0; k < 10; ++k) {
      const double t = k / 10.0;
      dense.push_back({corners[c].x_m + t * (corners[c + 1].x_m - corners[c].x_m),
                       corners[c].y_m + t * (corners[c + 1].y_m - corners[c].y_m)});
    }
  }
  dense.push_back(corners[4]);
  const Polyline s = simplify_polyline(dense, 0.1);
  ASSERT_EQ(s.size(), 5u);
  for (int c = 0; c < 5; ++c)
    EXPECT_EQ(s[static_cast<std::size_t>(c)], corners[c]);
  // Large enough a tolerance swallows the zig-zag.
  EXPECT_EQ(simplify_polyline(dense, 1.5).size(), 2u);
}

TEST(Simplify, EveryDensePointWithinEpsilon) {
  ArcTurnSpec spec;
  spec.dheading_deg = 150.0;
  spec.dt_s = 0.05;
  spec.tail_m = 3.0;
  spec.position_noise_m = 0.05;  // irregular on purpose
  const Polyline dense = make_arc_turn(spec).points();
  for (double eps : {0.0, 0.01, 0.05, 0.2, 1.0}) {
    const Polyline s = simplify_polyline(dense, eps);
    EXPECT_EQ(s.front(), dense.front());
    EXPECT_EQ(s.back(), dense.back());
    EXPECT_LE(max_deviation_m(dense, s), eps) << eps;
    for (const Point& p : s)
      EXPECT_TRUE(contains(dense, p));  // vertices are input points
  }
}

TEST(Simplify, ArcNeedsFewerVertices) {
  const Polyline dense = circular_arc(3.0, 90.0, 0.01);
  const Polyline s = simplify_polyline(dense, 0.05);
  EXPECT_LT(s.size(), dense.size() / 20);
  // The chord of a 3 m arc strays R (1 - cos(theta / 2)) from it, so 0.05 m allows chords of
  // 20.9 degrees: at least 5 of them for 90 degrees. DP halves the arc until the pieces fit:
  // 90 -> 45 -> 22.5 (strays 0.058 m) -> 11.25 degrees, i.e. 8 segments.
  EXPECT_GE(s.size(), 6u);
  EXPECT_LE(s.size(), 9u);
}

TEST(Simplify, TinyInputsAndBadEpsilon) {
  EXPECT_TRUE(simplify_polyline({}, 0.1).empty());
  EXPECT_EQ(simplify_polyline({{1, 2}}, 0.1).size(), 1u);
  EXPECT_EQ(simplify_polyline({{1, 2}, {3, 4}}, 0.1).size(), 2u);
  // A closed loop: both ends coincide (a zero-length base segment); only the point on a straight
  // stretch may go.
  const Polyline loop = simplify_polyline({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 0}}, 0.1);
  EXPECT_EQ(loop, (Polyline{{0, 0}, {2, 0}, {2, 2}, {0, 0}}));
  EXPECT_THROW(simplify_polyline({{0, 0}, {1, 1}, {2, 0}}, -1.0), std::invalid_argument);
  EXPECT_THROW(simplify_polyline({{0, 0}, {1, 1}, {2, 0}}, std::nan("")), std::invalid_argument);
}

TEST(Simplify, LongInputNeedsNoRecursion) {
  // A spiral of 200k points whose every vertex is kept: deep splits, explicit stack only.
  Polyline dense;
  for (int i = 0; i < 200000; ++i) {
    const double a = 0.01 * i;
    dense.push_back({(1.0 + 0.001 * i) * std::cos(a), (1.0 + 0.001 * i) * std::sin(a)});
  }
  const Polyline s = simplify_polyline(dense, 1e-6);
  EXPECT_GT(s.size(), 1000u);
  EXPECT_EQ(s.back(), dense.back());
}

TEST(Simplify, MaxDeviationMeasuresWorstPoint) {
  const Polyline approx = {{0, 0}, {10, 0}};
  EXPECT_DOUBLE_EQ(max_deviation_m({{1, 0.5}, {5, -2}, {12, 0}}, approx), 2.0);
  EXPECT_DOUBLE_EQ(max_deviation_m({}, approx), 0.0);
  EXPECT_TRUE(std::isinf(max_deviation_m({{0, 0}}, {})));
}

TEST(Simplify, PiecewiseLinearStaysWithinEpsilonOfTheFit) {
  ArcTurnSpec spec;
  spec.dheading_deg = 120.0;
  spec.radius_m = 2.0;
  spec.lead_in_m = 2.0;
  spec.dt_s = 0.1;
  spec.position_noise_m = 0.1;
  const Polyline pts = make_arc_turn(spec).points();
  Polyline arc_only;  // where y = f(x) is single valued
  for (const Point& p : pts)
    if (p.y_m > 2.2 && p.x_m < 1.9) arc_only.push_back(p);
  for (const CurveFit& fit : {fit_arc_length_spline(pts), fit_poly4(arc_only)}) {
    const Polyline reference = fit.sample(0.001);
    std::size_t previous = 0;
    for (double eps : {0.2, 0.1, 0.05, 0.02, 0.01}) {
      const Polyline line = piecewise_linear(fit, eps);
      EXPECT_LE(max_deviation_m(reference, line), eps) << to_string(fit.kind) << " eps " << eps;
      EXPECT_EQ(line.front(), fit.evaluate(fit.domain_min));
      EXPECT_EQ(line.back(), fit.evaluate(fit.domain_max));
      EXPECT_GE(line.size(), previous) << "tighter tolerance, fewer vertices?";
      previous = line.size();
    }
  }
  EXPECT_THROW(piecewise_linear(fit_arc_length_spline(pts), 0.0), std::invalid_argument);
}

TEST(Simplify, PiecewiseLinearVertexCountFor90DegreeArc) {
  // Optimal: 0.05 m allows 20.9-degree chords on R = 3 m, so 5 segments (6 vertices) for 90
  // degrees; DP halves an arc until the pieces fit (8 segments here), so allow up to 9.
  const CurveFit arc = fit_arc_length_spline(circular_arc(3.0, 90.0, 0.1));
  const Polyline line = piecewise_linear(arc, 0.05);
  EXPECT_GE(line.size(), 6u);
  EXPECT_LE(line.size(), 9u);
  ArcTurnSpec spec;
  spec.dheading_deg = 90.0;
  spec.radius_m = 3.0;
  spec.lead_in_m = 2.0;
  const Polyline with_lead_in =
      piecewise_linear(fit_arc_length_spline(make_arc_turn(spec).points()), 0.05);
  std::cout << "piecewise_linear(eps 0.05): 90 deg R 3 m arc -> " << line.size()
            << " vertices; with 2 m lead-in -> " << with_lead_in.size() << " vertices\n";
  RecordProperty("vertices_90deg_R3_eps005", std::to_string(line.size()));
  EXPECT_LE(with_lead_in.size(), line.size() + 3);
}
