#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/curve_fit.hpp"
#include "kinematics/geometry.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::arc_turn_length_m;
using avk::testing::arc_turn_point;
using avk::testing::ArcTurnSpec;
using avk::testing::circular_arc;
using avk::testing::make_arc_turn;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Dense noise-free samples of the analytic turn, the "truth" a fit of noisy samples aims at.
Polyline truth_of(const ArcTurnSpec& spec) {
  Polyline out;
  const double total = arc_turn_length_m(spec);
  for (double s = 0.0; s < total; s += 0.01)
    out.push_back(arc_turn_point(spec, s, nullptr));
  out.push_back(arc_turn_point(spec, total, nullptr));
  return out;
}

// Sum of |heading change| along the curve beyond the net change: 0 for a curve that turns one way.
double excess_turning_deg(const CurveFit& fit, double step) {
  double prev = fit.heading_deg_at(fit.domain_min);
  const double first = prev;
  double total = 0.0;
  for (double p = fit.domain_min + step; p <= fit.domain_max; p += step) {
    const double h = fit.heading_deg_at(p);
    total += std::abs(h - prev);
    prev = h;
  }
  return total - std::abs(fit.heading_deg_at(fit.domain_max) - first);
}

void expect_check_names(const CurveFit& fit, const std::string& field) {
  try {
    fit.check();
    ADD_FAILURE() << "check() accepted a fit with a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(CurveFit, KindNamesRoundTrip) {
  for (FitKind k : {FitKind::poly4_xy, FitKind::arc_length_spline})
    EXPECT_EQ(fit_kind_from_string(to_string(k)), k);
  EXPECT_STREQ(to_string(FitKind::poly4_xy), "poly4_xy");
  EXPECT_STREQ(to_string(FitKind::arc_length_spline), "arc_length_spline");
  EXPECT_FALSE(fit_kind_from_string("poly4").has_value());
  EXPECT_FALSE(fit_kind_from_string("").has_value());
}

TEST(CurveFit, Poly4RecoversKnownQuartic) {
  const double a[5] = {0.3, -1.2, 0.05, 0.8, -0.02};
  const auto f = [&](double x) { return (((a[4] * x + a[3]) * x + a[2]) * x + a[1]) * x + a[0]; };
  Polyline pts;
  for (int i = 0; i < 40; ++i) {
    const double x = -2.0 + 5.0 * std::pow(i / 39.0, 1.3);  // uneven spacing on purpose
    pts.push_back({x, f(x)});
  }
  const CurveFit fit = fit_poly4(pts);
  EXPECT_EQ(fit.kind, FitKind::poly4_xy);
  EXPECT_NO_THROW(fit.check());
  EXPECT_DOUBLE_EQ(fit.domain_min, -2.0);
  EXPECT_DOUBLE_EQ(fit.domain_max, 3.0);
  const auto c = unscaled_poly4_coefficients(fit);
  for (int k = 0; k < 5; ++k)
    EXPECT_NEAR(c[k], a[k], 1e-9) << "coefficient " << k;
  for (int i = 0; i <= 200; ++i) {
    const double x = -2.0 + 5.0 * i / 200.0;
    const Point p = fit.evaluate(x);
    EXPECT_DOUBLE_EQ(p.x_m, x);
    EXPECT_NEAR(p.y_m, f(x), 1e-9);
  }
  // Far from the origin the scaled form still reproduces the curve.
  Polyline far;
  for (int i = 0; i < 30; ++i) {
    const double x = 1000.0 + i * 0.5;
    far.push_back({x, f(x - 1000.0)});
  }
  const CurveFit far_fit = fit_poly4(far);
  for (int i = 0; i <= 58; ++i) {
    const double x = 1000.0 + i * 0.25;
    EXPECT_NEAR(far_fit.evaluate(x).y_m, f(x - 1000.0), 1e-8);
  }
}

TEST(CurveFit, Poly4HeadingFollowsSlope) {
  Polyline pts;
  for (int i = 0; i <= 20; ++i) {
    const double x = 0.1 * i;
    pts.push_back({x, x * x});
  }
  const CurveFit fit = fit_poly4(pts);
  for (double x : {0.0, 0.5, 1.0, 2.0})
    EXPECT_NEAR(fit.heading_deg_at(x), rad_to_deg(std::atan2(1.0, 2.0 * x)), 1e-6) << x;
}

TEST(CurveFit, Poly4RejectsTooFewDistinctX) {
  EXPECT_THROW(fit_poly4({}), std::invalid_argument);
  EXPECT_THROW(fit_poly4({{0, 0}, {1, 1}, {2, 4}, {3, 9}}), std::invalid_argument);
  // Many samples but only four distinct x (a lead-in straight up the y axis, then three more).
  Polyline pts;
  for (int i = 0; i < 20; ++i)
    pts.push_back({0.0, 0.1 * i});
  pts.push_back({1.0, 2.0});
  pts.push_back({2.0, 2.5});
  pts.push_back({3.0, 2.7});
  EXPECT_THROW(fit_poly4(pts), std::invalid_argument);
  pts.push_back({4.0, 2.8});
  EXPECT_NO_THROW(fit_poly4(pts));
  EXPECT_THROW(fit_poly4({{0, 0}, {1, 1}, {2, 4}, {3, 9}, {kInf, 1}}), std::invalid_argument);
}

TEST(CurveFit, SplineReproducesStraightLine) {
  const double heading = 30.0;
  const Point dir = {std::sin(deg_to_rad(heading)), std::cos(deg_to_rad(heading))};
  Polyline pts;
  for (int i = 0; i <= 60; ++i)
    pts.push_back({1.0 + 0.1 * i * dir.x_m, -2.0 + 0.1 * i * dir.y_m});
  const CurveFit fit = fit_arc_length_spline(pts);
  EXPECT_NO_THROW(fit.check());
  EXPECT_EQ(fit.domain_min, 0.0);
  EXPECT_NEAR(fit.domain_max, 6.0, 1e-9);
  for (int i = 0; i <= 120; ++i) {
    const double s = 6.0 * i / 120.0;
    const Point p = fit.evaluate(s);
    EXPECT_NEAR(p.x_m, 1.0 + s * dir.x_m, 1e-9);
    EXPECT_NEAR(p.y_m, -2.0 + s * dir.y_m, 1e-9);
    EXPECT_NEAR(fit.heading_deg_at(s), heading, 1e-6);
  }
  EXPECT_LT(rms_distance_m(pts, fit), 1e-9);
}

TEST(CurveFit, SplineReproducesCircularArc) {
  const double radius = 3.0;
  const Polyline pts = circular_arc(radius, 120.0, 0.05);
  const CurveFit fit = fit_arc_length_spline(pts);
  EXPECT_NO_THROW(fit.check());
  EXPECT_NEAR(fit.domain_max, radius * deg_to_rad(120.0), 5e-4);
  double worst = 0.0;
  for (const Point& p : fit.sample(0.01))
    worst = std::max(worst, std::abs(distance_m(p, {radius, 0.0}) - radius));
  EXPECT_LT(worst, 5e-4);
  EXPECT_LT(rms_distance_m(pts, fit), 2e-4);
  EXPECT_LT(distance_m(fit.control_points.front(), {0.0, 0.0}), 1e-3);
  EXPECT_LT(distance_m(fit.evaluate(fit.domain_max), pts.back()), 1e-3);
}

TEST(CurveFit, SplineHeadingAlongArcIsAnalytic) {
  const double radius = 4.0;
  const Polyline pts = circular_arc(radius, 150.0, 0.1);
  const CurveFit fit = fit_arc_length_spline(pts);
  double worst_by_s = 0.0;
  double worst_by_position = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double s = fit.domain_max * i / 100.0;
    const double h = fit.heading_deg_at(s);
    // The parameter stands for arc length, and the tangent of a circle is normal to the radius.
    worst_by_s = std::max(worst_by_s, std::abs(h - rad_to_deg(s / radius)));
    const Point p = fit.evaluate(s);
    const double a = std::atan2(p.y_m, radius - p.x_m);
    worst_by_position = std::max(worst_by_position, std::abs(h - rad_to_deg(a)));
  }
  EXPECT_LT(worst_by_s, 0.5);
  EXPECT_LT(worst_by_position, 0.2);
  RecordProperty("heading_error_by_s_deg", std::to_string(worst_by_s));
}

TEST(CurveFit, SplineFollowsLeadInAndHalfTurn) {
  ArcTurnSpec spec;
  spec.dheading_deg = 180.0;
  spec.lead_in_m = 3.0;
  spec.radius_m = 2.0;
  spec.dt_s = 0.1;
  const Polyline pts = make_arc_turn(spec).points();
  const CurveFit fit = fit_arc_length_spline(pts);
  EXPECT_NO_THROW(fit.check());
  EXPECT_NEAR(fit.domain_max, arc_turn_length_m(spec), 0.01);
  EXPECT_LT(rms_distance_m(pts, fit), 0.01);
  EXPECT_LT(rms_distance_m(truth_of(spec), fit), 0.01);
  EXPECT_LT(distance_m(fit.control_points.front(), {0.0, 0.0}), 0.01);
  EXPECT_LT(distance_m(fit.evaluate(fit.domain_max), pts.back()), 0.02);
  EXPECT_NEAR(fit.heading_deg_at(fit.domain_max), 180.0, 1.0);
  // Along the lead-in and, past the smoothed curvature jump, along the arc. A cubic cannot turn
  // the synthetic turn's instant curvature jump, and the least-squares error of that corner
  // rings back along the lead-in by a degree or two.
  for (double s = 0.0; s < 2.0; s += 0.1)
    EXPECT_NEAR(fit.heading_deg_at(s), 0.0, 3.0) << s;
  for (double s = 4.5; s <= fit.domain_max; s += 0.1) {
    double truth_deg = 0.0;
    arc_turn_point(spec, s, &truth_deg);
    EXPECT_NEAR(fit.heading_deg_at(s), truth_deg, 1.5) << s;
  }
  EXPECT_LT(excess_turning_deg(fit, 0.05), 5.0);
}

TEST(CurveFit, SplineDoesNotWiggleOnNoisyTurns) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    ArcTurnSpec spec;
    spec.dheading_deg = 90.0;
    spec.lead_in_m = 2.0;
    spec.radius_m = 3.0;
    spec.dt_s = 0.1;
    spec.position_noise_m = 0.3;
    spec.seed = seed;
    const Polyline pts = make_arc_turn(spec).points();
    const CurveFit fit = fit_arc_length_spline(pts);
    EXPECT_LT(rms_distance_m(truth_of(spec), fit), 0.15) << seed;
    EXPECT_LT(excess_turning_deg(fit, 0.05), 15.0) << seed;
    // Without the noise-driven smoothing the same data makes the curve turn back and forth.
    ArcSplineOptions stiffless;
    stiffless.noise_smoothing_gain = 0.0;
    EXPECT_GT(excess_turning_deg(fit_arc_length_spline(pts, stiffless), 0.05),
              excess_turning_deg(fit, 0.05))
        << seed;
  }
}

TEST(CurveFit, NoiseEstimateMatchesSimulatedNoise) {
  for (double sigma : {0.05, 0.1, 0.3}) {
    ArcTurnSpec spec;
    spec.dheading_deg = 120.0;
    spec.dt_s = 0.1;
    spec.tail_m = 10.0;
    spec.position_noise_m = sigma;
    EXPECT_NEAR(estimate_position_noise_m(make_arc_turn(spec).points()), sigma, 0.2 * sigma);
  }
  EXPECT_LT(estimate_position_noise_m(circular_arc(3.0, 90.0, 0.25)), 1e-3);
}

TEST(CurveFit, SplineRejectsDegenerateInput) {
  EXPECT_THROW(fit_arc_length_spline({}), std::invalid_argument);
  EXPECT_THROW(fit_arc_length_spline({{0, 0}, {0, 0}, {0, 0}}), std::invalid_argument);
  EXPECT_THROW(fit_arc_length_spline({{0, 0}, {0, 1}}), std::invalid_argument);
  EXPECT_THROW(fit_arc_length_spline({{0, 0}, {0, 1}, {std::nan(""), 2}}), std::invalid_argument);
  ArcSplineOptions bad;
  bad.knot_spacing_m = 0.0;
  EXPECT_THROW(fit_arc_length_spline(circular_arc(3, 90, 0.1), bad), std::invalid_argument);
  EXPECT_NO_THROW(fit_arc_length_spline({{0, 0}, {0, 1}, {0.5, 2}}));
}

TEST(CurveFit, SampleKeepsStepAndChordErrorBounds) {
  ArcTurnSpec spec;
  spec.dheading_deg = 120.0;
  spec.radius_m = 2.0;
  const Polyline pts = make_arc_turn(spec).points();
  // A poly4 fit of the arc part alone, where y = f(x) is single valued.
  Polyline arc_only;
  for (const Point& p : pts)
    if (p.y_m > spec.lead_in_m && p.x_m < 1.9) arc_only.push_back(p);
  for (const CurveFit& fit : {fit_arc_length_spline(pts), fit_poly4(arc_only)}) {
    for (double step : {0.5, 0.1, 0.02}) {
      const Polyline line = fit.sample(step);
      ASSERT_GE(line.size(), 2u);
      EXPECT_EQ(line.front(), fit.evaluate(fit.domain_min));
      EXPECT_EQ(line.back(), fit.evaluate(fit.domain_max));
      for (std::size_t i = 1; i < line.size(); ++i)
        ASSERT_LE(distance_m(line[i - 1], line[i]), step + 1e-12) << to_string(fit.kind);
    }
    const Polyline reference = fit.sample(0.001);
    for (double chord_error : {0.05, 0.01, 0.001}) {
      const Polyline coarse = fit.sample(kInf, chord_error);
      double worst = 0.0;
      for (const Point& p : reference)
        worst = std::max(worst, distance_to_polyline_m(p, coarse));
      EXPECT_LE(worst, chord_error) << to_string(fit.kind);
    }
  }
  EXPECT_THROW(fit_arc_length_spline(pts).sample(0.0), std::invalid_argument);
}

TEST(CurveFit, FitCurveDispatchesOnKind) {
  const Polyline pts = circular_arc(3.0, 60.0, 0.1);
  EXPECT_EQ(fit_curve(FitKind::poly4_xy, pts), fit_poly4(pts));
  EXPECT_EQ(fit_curve(FitKind::arc_length_spline, pts), fit_arc_length_spline(pts));
  EXPECT_NE(fit_curve(FitKind::poly4_xy, pts), fit_curve(FitKind::arc_length_spline, pts));
}

TEST(CurveFit, CheckRejectsEachInconsistentField) {
  const Polyline pts = circular_arc(3.0, 60.0, 0.1);
  const CurveFit poly = fit_poly4(pts);
  const CurveFit spline = fit_arc_length_spline(pts);
  EXPECT_NO_THROW(poly.check());
  EXPECT_NO_THROW(spline.check());

  CurveFit f = poly;
  f.coefficients.pop_back();
  expect_check_names(f, "coefficients");
  f = poly;
  f.coefficients[2] = std::nan("");
  expect_check_names(f, "coefficients");
  f = poly;
  f.scale = 0.0;
  expect_check_names(f, "scale");
  f = poly;
  f.center = kInf;
  expect_check_names(f, "center");
  f = poly;
  std::swap(f.domain_min, f.domain_max);
  expect_check_names(f, "domain_max");
  f = poly;
  f.knots = {0, 0, 0, 0};
  expect_check_names(f, "knots");
  f = poly;
  f.kind = static_cast<FitKind>(7);
  expect_check_names(f, "kind");

  f = spline;
  std::swap(f.knots[4], f.knots[5]);
  expect_check_names(f, "knots");
  f = spline;
  f.knots.pop_back();
  expect_check_names(f, "knots");
  f = spline;
  f.control_points.push_back({1, 1});
  expect_check_names(f, "knots");
  f = spline;
  f.control_points[1].y_m = std::nan("");
  expect_check_names(f, "control_points");
  f = spline;
  f.control_points.resize(3);
  f.knots.resize(7);
  expect_check_names(f, "control_points");
  f = spline;
  f.knots.front() = -1.0;  // no longer clamped at domain_min
  expect_check_names(f, "knots");
  f = spline;
  f.domain_max = kInf;
  expect_check_names(f, "domain_max");
  f = spline;
  f.coefficients = {1, 2, 3, 4, 5};
  expect_check_names(f, "coefficients");
}

// The thesis's y = f(x) against the arc-length spline on simulated normalised turns, each
// measured against the samples it was fitted to (and the spline also against the noise-free
// truth). Prints the table quoted in the closing note.
TEST(CurveFit, ArcSplineBeatsPoly4OnSyntheticTurns) {
  struct Cell {
    double poly_sum = 0.0, spline_sum = 0.0, truth_sum = 0.0;
    int n = 0, poly_failed = 0;
  };
  const double noises[] = {0.0, 0.05, 0.1, 0.3};
  int cases = 0;
  int wins = 0;
  int clean_cases = 0;
  int clean_wins = 0;
  std::ostringstream table;
  table << "RMS distance (m) of the fit to its own samples; mean over lead-in {1,2,3} m x radius\n"
           "{2,4,6} m x dt {0.25,0.1} s; 'truth' = spline vs noise-free curve; * = poly4 threw\n"
           "(too few distinct x) on some cases, mean over the rest\n"
           " dpsi |       noise-free        |      sigma = 0.1 m      |      sigma = 0.3 m\n"
           "  deg |  poly4  spline  truth   |  poly4  spline  truth   |  poly4  spline  truth\n";
  for (int dpsi = 10; dpsi <= 170; dpsi += 10) {
    char row[256];
    int len = std::snprintf(row, sizeof row, " %4d ", dpsi);
    for (double noise : noises) {
      Cell cell;
      unsigned seed = 1;
      for (double lead : {1.0, 2.0, 3.0}) {
        for (double radius : {2.0, 4.0, 6.0}) {
          for (double dt : {0.25, 0.1}) {
            ArcTurnSpec spec;
            spec.dheading_deg = dpsi;
            spec.lead_in_m = lead;
            spec.radius_m = radius;
            spec.dt_s = dt;
            spec.position_noise_m = noise;
            spec.seed = seed++ + 100u * static_cast<unsigned>(dpsi);
            const Polyline pts = make_arc_turn(spec).points();
            const CurveFit spline = fit_arc_length_spline(pts);
            const double spline_rms = rms_distance_m(pts, spline);
            double poly_rms = kInf;
            try {
              poly_rms = rms_distance_m(pts, fit_poly4(pts));
              cell.poly_sum += poly_rms;
            } catch (const std::invalid_argument&) {
              ++cell.poly_failed;
            }
            cell.spline_sum += spline_rms;
            cell.truth_sum += rms_distance_m(truth_of(spec), spline);
            ++cell.n;
            ++cases;
            const bool win = spline_rms < poly_rms;
            wins += win;
            if (noise == 0.0) {
              ++clean_cases;
              clean_wins += win;
            }
          }
        }
      }
      if (noise == 0.05) continue;  // counted, not printed: keeps the table narrow
      const int ok = cell.n - cell.poly_failed;
      len += std::snprintf(row + len, sizeof row - static_cast<std::size_t>(len),
                           "| %6.3f%c %6.3f %6.3f  ", ok > 0 ? cell.poly_sum / ok : kInf,
                           cell.poly_failed ? '*' : ' ', cell.spline_sum / cell.n,
                           cell.truth_sum / cell.n);
    }
    table << row << "\n";
  }
  table << "spline RMS below poly4 RMS in " << wins << "/" << cases << " turns (noise-free "
        << clean_wins << "/" << clean_cases << ")\n";
  std::cout << table.str();
  RecordProperty("spline_wins", std::to_string(wins) + "/" + std::to_string(cases));
  EXPECT_EQ(clean_wins, clean_cases);
  EXPECT_GE(wins, static_cast<int>(0.95 * cases));
}
