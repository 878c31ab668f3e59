#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sim/catamaran.hpp"
#include "sim/environment.hpp"

using namespace avk::sim;

namespace {

constexpr double kTol = 1e-12;

EnvironmentConfig windy(double mean_mps, double from_deg, double sigma_mps = 0.0,
                        std::uint64_t seed = 1) {
  EnvironmentConfig c;
  c.wind.mean_speed_mps = mean_mps;
  c.wind.from_deg = from_deg;
  c.wind.gust_sigma_mps = sigma_mps;
  c.seed = seed;
  return c;
}

}  // namespace

TEST(Environment, CurrentFlowsTowardItsDirection) {
  EnvironmentConfig c;
  c.current = {0.5, 90.0};
  Environment env(c);
  EXPECT_NEAR(env.current_velocity_en_mps().x(), 0.5, kTol);
  EXPECT_NEAR(env.current_velocity_en_mps().y(), 0.0, kTol);
  // Heading north, water going east comes from port and goes to starboard: +v.
  EXPECT_NEAR(env.current_velocity_body_mps(0.0).x(), 0.0, kTol);
  EXPECT_NEAR(env.current_velocity_body_mps(0.0).y(), 0.5, kTol);
  // Heading east: straight astern, +u.
  EXPECT_NEAR(env.current_velocity_body_mps(90.0).x(), 0.5, kTol);
  EXPECT_NEAR(env.current_velocity_body_mps(90.0).y(), 0.0, kTol);
  // Heading south-east (135): the eastward water is half on the bow, half to port.
  EXPECT_NEAR(env.current_velocity_body_mps(135.0).x(), 0.5 * std::sqrt(0.5), kTol);
  EXPECT_NEAR(env.current_velocity_body_mps(135.0).y(), -0.5 * std::sqrt(0.5), kTol);
}

TEST(Environment, WindBlowsAwayFromItsDirection) {
  Environment env(windy(4.0, 0.0));
  EXPECT_NEAR(env.wind_velocity_en_mps().x(), 0.0, kTol);
  EXPECT_NEAR(env.wind_velocity_en_mps().y(), -4.0, kTol);
  Environment west(windy(4.0, 270.0));
  EXPECT_NEAR(west.wind_velocity_en_mps().x(), 4.0, kTol);
  EXPECT_NEAR(west.wind_velocity_en_mps().y(), 0.0, kTol);
}

TEST(Environment, WindLoadOnAHullAtRest) {
  const CatamaranParams m200 = CatamaranParams::m200();
  Environment env(windy(5.0, 0.0));
  const WindConfig& w = env.config().wind;
  const double q = 0.5 * w.air_density_kg_m3 * 25.0;
  const double frontal = m200.beam_m * w.windage_height_m;
  const double lateral = m200.length_m * w.windage_height_m;

  // Head wind: pushes straight astern.
  Eigen::Vector3d head = env.wind_load_body(0.0, Eigen::Vector3d::Zero(), m200);
  EXPECT_NEAR(head.x(), -q * w.drag_coefficient_x * frontal, 1e-9);
  EXPECT_NEAR(head.y(), 0.0, 1e-9);
  EXPECT_NEAR(head.z(), 0.0, 1e-9);

  // Heading east, wind from the north: on the port beam, pushes to starboard, and the forward
  // centre of pressure turns the bow to starboard (downwind).
  Eigen::Vector3d beam = env.wind_load_body(90.0, Eigen::Vector3d::Zero(), m200);
  const double y = q * w.drag_coefficient_y * lateral;
  EXPECT_NEAR(beam.x(), 0.0, 1e-9);
  EXPECT_NEAR(beam.y(), y, 1e-9);
  EXPECT_NEAR(beam.z(), w.pressure_centre_x_fraction_of_length * m200.length_m * y, 1e-9);

  // Explicit areas replace the ones derived from the hull.
  EnvironmentConfig c = windy(5.0, 0.0);
  c.wind.frontal_area_m2 = 2.0;
  Environment explicit_area(c);
  EXPECT_NEAR(explicit_area.wind_load_body(0.0, Eigen::Vector3d::Zero(), m200).x(),
              -q * w.drag_coefficient_x * 2.0, 1e-9);
}

TEST(Environment, WindLoadCountsOnlyTheWind) {
  const CatamaranParams otter = CatamaranParams::otter();
  // No wind: a moving hull feels no extra load (still-air drag is in the hull damping).
  Environment calm(EnvironmentConfig{});
  const Eigen::Vector3d moving(2.0, -0.3, 0.4);
  EXPECT_EQ(calm.wind_load_body(33.0, moving, otter), Eigen::Vector3d::Zero());
  // Running before the wind at the wind's speed: the apparent wind is 0, so the load is exactly
  // what the still-air drag would have been, reversed (the wind removes it).
  Environment env(windy(3.0, 180.0));  // blowing north
  const Eigen::Vector3d load = env.wind_load_body(0.0, Eigen::Vector3d(3.0, 0.0, 0.0), otter);
  const WindConfig& w = env.config().wind;
  EXPECT_NEAR(
      load.x(),
      0.5 * w.air_density_kg_m3 * w.drag_coefficient_x * otter.beam_m * w.windage_height_m * 9.0,
      1e-9);
}

TEST(Environment, GaussMarkovGustStatistics) {
  const double sigma = 1.5, tau = 5.0, dt = 0.1;
  EnvironmentConfig c = windy(6.0, 200.0, sigma, 42);
  c.wind.gust_time_constant_s = tau;
  Environment env(c);
  const int n = 2'000'000;  // 200 000 s, 20 000 time constants
  double sum = 0.0, sum_sq = 0.0, sum_lag = 0.0;
  double prev = env.gust_mps();
  for (int i = 0; i < n; ++i) {
    env.advance(dt);
    const double g = env.gust_mps();
    sum += g;
    sum_sq += g * g;
    sum_lag += g * prev;
    prev = g;
  }
  const double mean = sum / n;
  const double var = sum_sq / n - mean * mean;
  EXPECT_NEAR(std::sqrt(var), sigma, 0.1 * sigma);
  EXPECT_NEAR(std::sqrt(var), sigma, 0.02 * sigma);  // what 20 000 time constants really give
  EXPECT_NEAR(mean, 0.0, 0.05 * sigma);
  // One-step correlation of a first-order process: e^(−dt/τ).
  EXPECT_NEAR((sum_lag / n - mean * mean) / var, std::exp(-dt / tau), 0.005);
}

TEST(Environment, GustsAreDeterministicForASeed) {
  auto run = [](std::uint64_t seed) {
    Environment env(windy(5.0, 0.0, 1.0, seed));
    std::vector<double> gusts;
    for (int i = 0; i < 100; ++i) {
      env.advance(0.01);
      gusts.push_back(env.gust_mps());
    }
    return gusts;
  };
  EXPECT_EQ(run(7), run(7));
  EXPECT_NE(run(7), run(8));
}

TEST(Environment, NoGustsWithoutSigma) {
  Environment env(windy(5.0, 0.0, 0.0));
  for (int i = 0; i < 100; ++i)
    env.advance(0.3);
  EXPECT_EQ(env.gust_mps(), 0.0);
  EXPECT_EQ(env.wind_speed_mps(), 5.0);
}

TEST(Environment, WindSpeedNeverNegative) {
  EnvironmentConfig c = windy(0.5, 0.0, 3.0, 3);
  Environment env(c);
  bool clipped = false;
  for (int i = 0; i < 1000; ++i) {
    env.advance(1.0);
    EXPECT_GE(env.wind_speed_mps(), 0.0);
    clipped = clipped || env.gust_mps() < -0.5;
  }
  EXPECT_TRUE(clipped);
}

TEST(Environment, RejectsInvalidConfig) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EnvironmentConfig c;
  c.current.speed_mps = -1.0;
  EXPECT_THROW(Environment{c}, std::invalid_argument);
  c = {};
  c.wind.from_deg = nan;
  EXPECT_THROW(Environment{c}, std::invalid_argument);
  c = {};
  c.wind.gust_time_constant_s = 0.0;
  EXPECT_THROW(Environment{c}, std::invalid_argument);
  c = {};
  c.wind.gust_sigma_mps = -0.1;
  EXPECT_THROW(Environment{c}, std::invalid_argument);
  c = {};
  c.wind.lateral_area_m2 = -1.0;
  EXPECT_THROW(Environment{c}, std::invalid_argument);
  Environment env(EnvironmentConfig{});
  EXPECT_THROW(env.advance(-0.1), std::invalid_argument);
  EXPECT_THROW(env.advance(nan), std::invalid_argument);
}
