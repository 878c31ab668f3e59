#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "kinematics/path_approach.hpp"

namespace {

using avk::kinematics::closest_approach;
using avk::kinematics::Contact;
using avk::kinematics::TimedPath;
using avk::kinematics::TimedPoint;

// A straight run from (x, y) on a course (deg clockwise from north) at speed, sampled every dt.
TimedPath straight(double x, double y, double course_deg, double speed_mps, double t0, double t1,
                   double dt = 1.0) {
  TimedPath p;
  const double c = course_deg * std::numbers::pi / 180.0;
  for (double t = t0; t <= t1 + 1e-9; t += dt)
    p.push_back(
        {t, x + std::sin(c) * speed_mps * (t - t0), y + std::cos(c) * speed_mps * (t - t0)});
  return p;
}

// A circle of radius r about (cx, cy) run clockwise at speed from north of it.
TimedPath circle(double cx, double cy, double r, double speed_mps, double t1, double dt = 0.5) {
  TimedPath p;
  for (double t = 0.0; t <= t1 + 1e-9; t += dt) {
    const double a = speed_mps * t / r;
    p.push_back({t, cx + r * std::sin(a), cy + r * std::cos(a)});
  }
  return p;
}

TimedPath transformed(const TimedPath& p, double rot_deg, double dx, double dy, bool mirror) {
  const double a = rot_deg * std::numbers::pi / 180.0;
  TimedPath out;
  for (auto q : p) {
    if (mirror) q.x_m = -q.x_m;
    out.push_back({q.t_s, std::cos(a) * q.x_m - std::sin(a) * q.y_m + dx,
                   std::sin(a) * q.x_m + std::cos(a) * q.y_m + dy});
  }
  return out;
}

TEST(PathApproach, HeadOnVehiclesMeetHalfwayAtTheClosingTime) {
  // 200 m apart, closing at 1.5 + 0.5 m/s: they meet after 100 s, 150 m from the first.
  const auto a = straight(0, 0, 0, 1.5, 0, 300);
  const auto b = straight(0, 200, 180, 0.5, 0, 300);
  const auto cpa = closest_approach(a, b);
  EXPECT_NEAR(cpa.distance_m, 0.0, 1e-9);
  EXPECT_NEAR(cpa.time_s, 100.0, 1e-9);
}

TEST(PathApproach, CrossingCoursesMatchTheAnalyticCpa) {
  // a north from the origin at 1 m/s; b east from (-100, 50) at 1 m/s. Relative position
  // r(t) = (100 - t, t - 50): the minimum is at t = 75 s, |r| = 25 sqrt(2).
  const auto a = straight(0, 0, 0, 1.0, 0, 200, 7.0);  // sample times that miss t = 75
  const auto b = straight(-100, 50, 90, 1.0, 0, 200, 3.0);
  const auto cpa = closest_approach(a, b);
  EXPECT_NEAR(cpa.distance_m, 25.0 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(cpa.time_s, 75.0, 1e-9);
}

TEST(PathApproach, AgreesWithTheContactCpaForAStraightContact) {
  const auto own = circle(0, 0, 30, 1.2, 120);
  const Contact c{80.0, -20.0, 300.0, 0.9};
  const auto as_path = straight(c.x_m, c.y_m, c.course_deg, c.speed_mps, 0, 120, 0.25);
  const auto expected = avk::kinematics::closest_approach(own, c);
  const auto got = closest_approach(own, as_path);
  EXPECT_NEAR(got.distance_m, expected.distance_m, 1e-6);
  EXPECT_NEAR(got.time_s, expected.time_s, 1e-6);
}

TEST(PathApproach, IsSymmetricAndInvariantUnderRotationTranslationAndReflection) {
  const auto a = circle(10, 5, 25, 1.0, 90);
  const auto b = straight(60, -40, 320, 1.1, 0, 90, 2.0);
  const auto base = closest_approach(a, b);
  const auto swapped = closest_approach(b, a);
  EXPECT_NEAR(swapped.distance_m, base.distance_m, 1e-9);
  EXPECT_NEAR(swapped.time_s, base.time_s, 1e-9);
  for (const bool mirror : {false, true}) {
    for (const double rot : {0.0, 37.0, 190.0}) {
      const auto moved = closest_approach(transformed(a, rot, 500, -250, mirror),
                                          transformed(b, rot, 500, -250, mirror));
      EXPECT_NEAR(moved.distance_m, base.distance_m, 1e-6) << rot << (mirror ? " mirrored" : "");
      EXPECT_NEAR(moved.time_s, base.time_s, 1e-6);
    }
  }
}

TEST(PathApproach, OnlyTheCommonTimeSpanCounts) {
  // b only exists from t = 150 s, when a has long passed the crossing point.
  const auto a = straight(0, 0, 0, 1.0, 0, 300);
  const auto b = straight(-10, 100, 90, 1.0, 150, 300);
  const auto cpa = closest_approach(a, b);
  EXPECT_GE(cpa.time_s, 150.0);
  EXPECT_GT(cpa.distance_m, 40.0);
}

TEST(PathApproach, CorridorsBringTheEdgesCloser) {
  const auto a = straight(0, 0, 0, 1.0, 0, 100, 5.0);
  const auto b = straight(30, 0, 0, 1.0, 0, 100, 5.0);  // parallel, 30 m abeam
  EXPECT_NEAR(closest_approach(a, b).distance_m, 30.0, 1e-9);
  const std::vector<double> wa(a.size(), 4.0), wb(b.size(), 6.0);
  EXPECT_NEAR(closest_approach(a, b, wa, wb).distance_m, 20.0, 1e-9);
  const std::vector<double> wide(a.size(), 20.0);
  EXPECT_EQ(closest_approach(a, b, wide, wide).distance_m, 0.0);
}

TEST(PathApproach, BadPathsAreNamed) {
  const auto a = straight(0, 0, 0, 1.0, 0, 10);
  EXPECT_THROW(closest_approach(TimedPath{}, a), std::invalid_argument);
  EXPECT_THROW(closest_approach(a, straight(0, 0, 0, 1.0, 20, 30)), std::invalid_argument);
  EXPECT_THROW(closest_approach(a, a, std::vector<double>{1.0}), std::invalid_argument);
}

TEST(PathApproach, PositionIsHeldAtThePathsEnds) {
  const TimedPath p{{0, 0, 0}, {10, 10, 0}};
  EXPECT_EQ(avk::kinematics::position_at(p, -5).x_m, 0.0);
  EXPECT_EQ(avk::kinematics::position_at(p, 5).x_m, 5.0);
  EXPECT_EQ(avk::kinematics::position_at(p, 50).x_m, 10.0);
}

}  // namespace
