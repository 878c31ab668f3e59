#include <gtest/gtest.h>

#include <cmath>

#include "sim/sensors.hpp"

using namespace avk::sim;

namespace {
TruthSample truth_at(double t) {
  TruthSample s;
  s.t_s = t;
  s.x_m = 10.0;
  s.y_m = -5.0;
  s.heading_deg = 359.5;
  s.speed_over_ground_mps = 1.234;
  s.course_over_ground_deg = 20.0;
  return s;
}
}  // namespace

TEST(NavSensor, ExactWithoutNoise) {
  NavSensor s({}, 1);
  s.measure(truth_at(1.0));
  const auto out = s.deliver(1.0);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].x_m, 10.0);
  EXPECT_DOUBLE_EQ(out[0].heading_deg, 359.5);
  EXPECT_DOUBLE_EQ(out[0].speed_mps, 1.234);
}

TEST(NavSensor, NoiseHasTheConfiguredSpread) {
  SensorConfig c;
  c.gnss_sigma_m = 0.3;
  c.compass_sigma_deg = 1.0;
  NavSensor s(c, 42);
  double sx = 0, sxx = 0, sh = 0, shh = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    TruthSample t = truth_at(i * 0.1);
    t.heading_deg = 90.0;
    s.measure(t);
    const auto out = s.deliver(i * 0.1);
    ASSERT_EQ(out.size(), 1u);
    sx += out[0].x_m - 10.0;
    sxx += (out[0].x_m - 10.0) * (out[0].x_m - 10.0);
    sh += out[0].heading_deg - 90.0;
    shh += (out[0].heading_deg - 90.0) * (out[0].heading_deg - 90.0);
  }
  EXPECT_NEAR(sx / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sxx / n), 0.3, 0.01);
  EXPECT_NEAR(std::sqrt(shh / n), 1.0, 0.03);
}

TEST(NavSensor, LatencyDelaysDeliveryAndStampsArrival) {
  SensorConfig c;
  c.latency_s = 0.3;
  NavSensor s(c, 1);
  s.measure(truth_at(1.0));
  EXPECT_TRUE(s.deliver(1.2).empty());
  const auto out = s.deliver(1.3);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].t_s, 1.3);
}

TEST(NavSensor, CourseAboveASpeedAndSpeedQuantum) {
  SensorConfig c;
  c.heading_from_course_above_mps = 0.5;
  c.speed_quantum_mps = 0.01;
  NavSensor s(c, 1);
  s.measure(truth_at(0.0));
  TruthSample slow = truth_at(0.1);
  slow.speed_over_ground_mps = 0.2;
  s.measure(slow);
  const auto out = s.deliver(1.0);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].heading_deg, 20.0);  // GNSS course
  EXPECT_DOUBLE_EQ(out[0].speed_mps, 1.23);
  EXPECT_DOUBLE_EQ(out[1].heading_deg, 359.5);  // compass below the speed
}
