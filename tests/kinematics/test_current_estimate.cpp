// A uniform current from steady legs: exact without noise, within its stated uncertainty with
// GNSS noise, rotating with the legs, and refused when the headings cannot separate it from a
// speed error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/current_estimate.hpp"

namespace {

using namespace avk::kinematics;

struct Sea {
  double current_east_mps = 0.0;
  double current_north_mps = 0.0;
  double speed_scale = 1.0;  // the vehicle makes this share of its commanded speed
  double gnss_sigma_m = 0.0;
};

// A leg on heading h at commanded speed u: 10 Hz for duration_s from (x0, y0).
SteadyLeg leg(const Sea& sea, double heading_deg, double u, double duration_s, std::mt19937_64& rng,
              double x0 = 0.0, double y0 = 0.0) {
  std::normal_distribution<double> noise(0.0, sea.gnss_sigma_m > 0.0 ? sea.gnss_sigma_m : 1.0);
  const double h = deg_to_rad(heading_deg);
  const double ve = sea.speed_scale * u * std::sin(h) + sea.current_east_mps;
  const double vn = sea.speed_scale * u * std::cos(h) + sea.current_north_mps;
  SteadyLeg l;
  l.heading_deg = heading_deg;
  l.water_speed_mps = u;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 0.1) {
    const double ex = sea.gnss_sigma_m > 0.0 ? noise(rng) : 0.0;
    const double ey = sea.gnss_sigma_m > 0.0 ? noise(rng) : 0.0;
    l.t_s.push_back(100.0 + t);
    l.x_m.push_back(x0 + ve * t + ex);
    l.y_m.push_back(y0 + vn * t + ey);
  }
  return l;
}

std::vector<SteadyLeg> legs_of(const Sea& sea, int n, unsigned seed, double duration_s = 8.0) {
  std::mt19937_64 rng(seed);
  std::vector<SteadyLeg> out;
  for (int i = 0; i < n; ++i) {
    const double u = 0.5 + 0.5 * (i % 3);
    out.push_back(leg(sea, std::fmod(47.0 * i, 360.0), u, duration_s, rng, 3.0 * i, -2.0 * i));
  }
  return out;
}

TEST(CurrentEstimate, GroundVelocityIsTheSlopeOfTheTrack) {
  std::mt19937_64 rng(1);
  const auto v = ground_velocity_mps(leg({0.1, -0.2, 1.0, 0.0}, 90.0, 1.0, 5.0, rng));
  EXPECT_NEAR(v[0], 1.1, 1e-12);
  EXPECT_NEAR(v[1], -0.2, 1e-12);
  SteadyLeg bad;
  bad.t_s = {0.0, 1.0};
  bad.x_m = {0.0, 1.0};
  bad.y_m = {0.0, 1.0};
  EXPECT_THROW(ground_velocity_mps(bad), std::invalid_argument);
}

TEST(CurrentEstimate, ExactWithoutNoise) {
  const Sea sea{0.2 * std::sin(deg_to_rad(60.0)), 0.2 * std::cos(deg_to_rad(60.0)), 0.93, 0.0};
  const auto r = estimate_current(legs_of(sea, 6, 1));
  ASSERT_TRUE(r.estimate) << r.why_not;
  EXPECT_NEAR(r.estimate->speed_mps(), 0.2, 1e-9);
  EXPECT_NEAR(r.estimate->toward_deg(), 60.0, 1e-6);
  EXPECT_NEAR(r.estimate->speed_scale, 0.93, 1e-9);
  EXPECT_NEAR(r.estimate->residual_rms_mps, 0.0, 1e-9);
}

TEST(CurrentEstimate, WithGnssNoiseTheTruthLiesWithinTheStatedUncertainty) {
  // The thesis' GNSS noise of the choppy sea (0.3 m) on 18 legs of 8 s, as before each turn of a
  // Figure 4-1 mission.
  int within = 0;
  const int trials = 40;
  for (int k = 0; k < trials; ++k) {
    const double toward = 23.0 * k;
    const double speed = 0.1 + 0.005 * k;
    const Sea sea{speed * std::sin(deg_to_rad(toward)), speed * std::cos(deg_to_rad(toward)), 0.95,
                  0.3};
    const auto r = estimate_current(legs_of(sea, 18, 100 + k));
    ASSERT_TRUE(r.estimate) << r.why_not;
    const auto& e = *r.estimate;
    EXPECT_NEAR(e.speed_mps(), speed, 0.05) << k;
    EXPECT_LT(std::abs(angle180_deg(e.toward_deg() - toward)), 15.0) << k;
    const double de = e.east_mps - sea.current_east_mps, dn = e.north_mps - sea.current_north_mps;
    // Mahalanobis distance of the truth under the stated covariance (2 dof: 95 % within 2.45).
    const double det = e.covariance[0] * e.covariance[2] - e.covariance[1] * e.covariance[1];
    ASSERT_GT(det, 0.0);
    const double m2 =
        (e.covariance[2] * de * de - 2.0 * e.covariance[1] * de * dn + e.covariance[0] * dn * dn) /
        det;
    within += std::sqrt(m2) <= 2.45 ? 1 : 0;
    EXPECT_GT(e.speed_sd_mps(), 0.0);
    EXPECT_LT(e.toward_sd_deg(), 15.0);
  }
  // About 95 % of trials; at least 85 % allows for the chance of 40 draws.
  EXPECT_GE(within, 34);
}

TEST(CurrentEstimate, TurnsWithTheLegs) {
  const Sea sea{0.15, -0.05, 1.0, 0.3};
  const auto base = estimate_current(legs_of(sea, 12, 7));
  ASSERT_TRUE(base.estimate);
  // The same legs and current rotated by 70 deg about the origin.
  std::vector<SteadyLeg> rotated = legs_of(sea, 12, 7);
  const double c = std::cos(deg_to_rad(70.0)), s = std::sin(deg_to_rad(70.0));
  for (SteadyLeg& l : rotated) {
    l.heading_deg += 70.0;
    for (std::size_t i = 0; i < l.t_s.size(); ++i) {
      const double x = l.x_m[i], y = l.y_m[i];
      l.x_m[i] = x * c + y * s;  // clockwise by 70 deg, as a heading turns
      l.y_m[i] = -x * s + y * c;
    }
  }
  const auto turned = estimate_current(rotated);
  ASSERT_TRUE(turned.estimate);
  EXPECT_NEAR(turned.estimate->speed_mps(), base.estimate->speed_mps(), 1e-9);
  EXPECT_NEAR(angle180_deg(turned.estimate->toward_deg() - base.estimate->toward_deg() - 70.0), 0.0,
              1e-6);
  EXPECT_NEAR(turned.estimate->speed_scale, base.estimate->speed_scale, 1e-9);
}

TEST(CurrentEstimate, MoreLegsKnowItBetter) {
  const Sea sea{0.1, 0.1, 1.0, 0.3};
  const auto few = estimate_current(legs_of(sea, 4, 3));
  const auto many = estimate_current(legs_of(sea, 36, 3));
  ASSERT_TRUE(few.estimate && many.estimate);
  EXPECT_LT(many.estimate->covariance[0] + many.estimate->covariance[2],
            few.estimate->covariance[0] + few.estimate->covariance[2]);
}

TEST(CurrentEstimate, OneHeadingCannotTellACurrentFromASpeedError) {
  std::mt19937_64 rng(1);
  const Sea sea{0.0, 0.2, 1.0, 0.0};
  const auto one = estimate_current({leg(sea, 10.0, 1.0, 8.0, rng)});
  EXPECT_FALSE(one.estimate);
  EXPECT_NE(one.why_not.find("2 headings"), std::string::npos) << one.why_not;
  const auto alike = estimate_current({leg(sea, 10.0, 1.0, 8.0, rng), leg(sea, 25.0, 1.5, 8.0, rng),
                                       leg(sea, 0.0, 0.5, 8.0, rng)});  // 25 deg at most
  EXPECT_FALSE(alike.estimate);
  EXPECT_NE(alike.why_not.find("apart"), std::string::npos) << alike.why_not;
}

}  // namespace
