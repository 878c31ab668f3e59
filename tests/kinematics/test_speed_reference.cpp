// Which speed the speed loop holds and how fast a straight-line prediction's error grows: legs
// flown exactly in a current under each reference are told apart, still water is not, the scatter
// of exact legs is nil and that of legs with a known velocity noise is that noise, and everything
// turns with the legs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"

namespace {

using namespace avk::kinematics;

WaterCurrent toward(double speed_mps, double toward_deg) {
  return {speed_mps * std::sin(deg_to_rad(toward_deg)),
          speed_mps * std::cos(deg_to_rad(toward_deg))};
}

struct Sea {
  WaterCurrent current;
  SpeedReference loop = SpeedReference::over_ground;
  double gnss_sigma_m = 0.0;
  double along_sigma_mps = 0.0;  // a constant velocity error per leg, along the heading
  double cross_sigma_mps = 0.0;  // and across it
  double leg_s = 20.0;
};

// A leg on heading h at commanded speed u, 10 Hz, its velocity the loop's plus the leg's error.
SteadyLeg leg(const Sea& sea, double heading_deg, double u, std::mt19937_64& rng) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto v = ground_velocity_for(heading_deg, u, sea.current, sea.loop);
  const double h = deg_to_rad(heading_deg);
  const double ea = sea.along_sigma_mps * unit(rng), ex = sea.cross_sigma_mps * unit(rng);
  const double ve = v[0] + ea * std::sin(h) + ex * std::cos(h);
  const double vn = v[1] + ea * std::cos(h) - ex * std::sin(h);
  SteadyLeg l;
  l.heading_deg = heading_deg;
  l.water_speed_mps = u;
  for (double t = 0.0; t <= sea.leg_s + 1e-9; t += 0.1) {
    l.t_s.push_back(50.0 + t);
    l.x_m.push_back(ve * t + sea.gnss_sigma_m * unit(rng));
    l.y_m.push_back(vn * t + sea.gnss_sigma_m * unit(rng));
  }
  return l;
}

// n legs on headings spread around the compass from `first_deg`, at 0.5, 1.0 and 1.5 m/s.
std::vector<SteadyLeg> legs_of(const Sea& sea, int n, unsigned seed, double first_deg = 10.0) {
  std::mt19937_64 rng(seed);
  std::vector<SteadyLeg> out;
  for (int i = 0; i < n; ++i)
    out.push_back(leg(sea, wrap360_deg(first_deg + 137.0 * i), 0.5 + 0.5 * (i % 3), rng));
  return out;
}

CurrentEstimate estimated(const std::vector<SteadyLeg>& legs) {
  const auto r = estimate_current(legs);
  if (!r.estimate) throw std::runtime_error(r.why_not);
  return *r.estimate;
}

// Clockwise by a, as a heading turns.
std::vector<SteadyLeg> rotated(std::vector<SteadyLeg> legs, double a_deg) {
  const double c = std::cos(deg_to_rad(a_deg)), s = std::sin(deg_to_rad(a_deg));
  for (SteadyLeg& l : legs) {
    l.heading_deg = wrap360_deg(l.heading_deg + a_deg);
    for (std::size_t i = 0; i < l.t_s.size(); ++i) {
      const double x = l.x_m[i], y = l.y_m[i];
      l.x_m[i] = x * c + y * s;
      l.y_m[i] = -x * s + y * c;
    }
  }
  return legs;
}

TEST(SpeedReference, NamesRoundTrip) {
  for (const auto r : {SpeedReference::over_ground, SpeedReference::through_water})
    EXPECT_EQ(parse_speed_reference(to_string(r)), r);
  EXPECT_EQ(std::string(to_string(SpeedReference::over_ground)), "over_ground");
  EXPECT_EQ(std::string(to_string(SpeedReference::through_water)), "through_water");
  EXPECT_FALSE(parse_speed_reference("ground"));
  EXPECT_FALSE(parse_speed_reference(""));
}

// Currents up to 0.3 m/s at 0.5 m/s and more: the loop gain stays within its clamp.
TEST(SpeedReference, GroundVelocityHoldsTheReferencesSpeed) {
  for (const WaterCurrent c : {toward(0.3, 60.0), toward(0.1, 200.0), toward(0.3, 310.0)}) {
    for (double heading = 0.0; heading < 360.0; heading += 15.0) {
      for (const double u : {0.5, 1.0, 1.5}) {
        const double h = deg_to_rad(heading);
        const auto og = ground_velocity_for(heading, u, c, SpeedReference::over_ground);
        EXPECT_NEAR(std::hypot(og[0], og[1]), u, 1e-12) << heading << " " << u;
        // The water-relative part points along the heading, forward.
        const double oe = og[0] - c.east_mps, on = og[1] - c.north_mps;
        EXPECT_NEAR(oe * std::cos(h) - on * std::sin(h), 0.0, 1e-12);
        EXPECT_GT(oe * std::sin(h) + on * std::cos(h), 0.0);
        const auto tw = ground_velocity_for(heading, u, c, SpeedReference::through_water);
        const double te = tw[0] - c.east_mps, tn = tw[1] - c.north_mps;
        EXPECT_NEAR(te * std::sin(h) + tn * std::cos(h), u, 1e-12);
        EXPECT_NEAR(te * std::cos(h) - tn * std::sin(h), 0.0, 1e-12);
      }
    }
  }
  // Still water: both are U along the heading.
  const auto still = ground_velocity_for(90.0, 1.2, {}, SpeedReference::over_ground);
  EXPECT_NEAR(still[0], 1.2, 1e-12);
  EXPECT_NEAR(still[1], 0.0, 1e-12);
}

TEST(SpeedReference, GroundVelocityInACurrentTooStrongIsClamped) {
  // 0.5 m/s straight across a heading of north at 0.2 m/s: no speed through the water makes
  // 0.2 m/s over ground, so the loop is taken at its least, a quarter of the commanded speed.
  const auto across = ground_velocity_for(0.0, 0.2, {0.5, 0.0}, SpeedReference::over_ground);
  EXPECT_NEAR(across[0], 0.5, 1e-12);
  EXPECT_NEAR(across[1], kMinSpeedLoopGain * 0.2, 1e-12);
  // A head current of 3.5 m/s at 1 m/s would need 4.5 m/s through the water: four times at most.
  const auto head = ground_velocity_for(0.0, 1.0, {0.0, -3.5}, SpeedReference::over_ground);
  EXPECT_NEAR(head[1], kMaxSpeedLoopGain * 1.0 - 3.5, 1e-12);
  // No commanded speed: the vehicle drifts with the water.
  const auto idle = ground_velocity_for(45.0, 0.0, {0.1, -0.2}, SpeedReference::over_ground);
  EXPECT_EQ(idle[0], 0.1);
  EXPECT_EQ(idle[1], -0.2);
}

TEST(SpeedReference, ExactLegsAreIdentifiedUnderEitherLoop) {
  for (const auto loop : {SpeedReference::over_ground, SpeedReference::through_water}) {
    for (const double speed : {0.1, 0.2, 0.3}) {
      Sea sea;
      sea.current = toward(speed, 75.0);
      sea.loop = loop;
      const auto legs = legs_of(sea, 9, 1);
      const CurrentEstimate c = estimated(legs);
      EXPECT_NEAR(c.east_mps, sea.current.east_mps, 1e-9);
      const auto e = identify_speed_reference(legs, c);
      EXPECT_EQ(e.legs, 9u);
      EXPECT_EQ(e.identified, loop) << to_string(loop) << " " << speed;
      const double right =
          loop == SpeedReference::over_ground ? e.rms_over_ground_mps : e.rms_through_water_mps;
      const double wrong =
          loop == SpeedReference::over_ground ? e.rms_through_water_mps : e.rms_over_ground_mps;
      EXPECT_NEAR(right, 0.0, 1e-9);
      // The hypotheses differ on a leg by about c · h: the wrong one's RMS is about its RMS.
      EXPECT_NEAR(wrong, e.separation_mps, 0.3 * e.separation_mps);
    }
  }
}

TEST(SpeedReference, NoisyLegsAreIdentifiedUnderEitherLoop) {
  // The M200's GNSS (0.3 m) and a gust-like velocity error per leg of 1 cm/s, 12 legs of 20 s.
  int trials = 0;
  for (const auto loop : {SpeedReference::over_ground, SpeedReference::through_water}) {
    for (const double speed : {0.1, 0.2, 0.3}) {
      for (const double dir : {0.0, 75.0, 200.0, 310.0}) {
        Sea sea;
        sea.current = toward(speed, dir);
        sea.loop = loop;
        sea.gnss_sigma_m = 0.3;
        sea.along_sigma_mps = 0.01;
        sea.cross_sigma_mps = 0.01;
        const auto legs = legs_of(sea, 12, 100 + static_cast<unsigned>(trials), dir / 3.0);
        const auto e = identify_speed_reference(legs, estimated(legs));
        EXPECT_EQ(e.identified, loop)
            << to_string(loop) << " " << speed << " toward " << dir << ": og "
            << e.rms_over_ground_mps << " tw " << e.rms_through_water_mps;
        ++trials;
      }
    }
  }
  EXPECT_EQ(trials, 24);
}

TEST(SpeedReference, StillWaterIsUndetermined) {
  for (const auto loop : {SpeedReference::over_ground, SpeedReference::through_water}) {
    Sea sea;
    sea.loop = loop;
    // Exact legs: both hypotheses fit perfectly; nothing separates them.
    const auto exact = legs_of(sea, 9, 2);
    const auto e = identify_speed_reference(exact, estimated(exact));
    EXPECT_FALSE(e.identified);
    EXPECT_NEAR(e.separation_mps, 0.0, 1e-9);
    // With noise the estimated "current" is noise, and so is its separation.
    sea.gnss_sigma_m = 0.3;
    sea.along_sigma_mps = 0.02;
    sea.cross_sigma_mps = 0.02;
    for (unsigned seed = 0; seed < 20; ++seed) {
      const auto legs = legs_of(sea, 12, 300 + seed);
      EXPECT_FALSE(identify_speed_reference(legs, estimated(legs)).identified) << seed;
    }
  }
}

TEST(SpeedReference, FewLegsAreUndetermined) {
  Sea sea;
  sea.current = toward(0.3, 30.0);
  const auto legs = legs_of(sea, 9, 3);
  const CurrentEstimate c = estimated(legs);
  const std::vector<SteadyLeg> two(legs.begin(), legs.begin() + 2);
  const auto e = identify_speed_reference(two, c);
  EXPECT_EQ(e.legs, 2u);
  EXPECT_FALSE(e.identified);
  EXPECT_FALSE(identify_speed_reference({}, c).identified);
  // A leg without a commanded speed says nothing about the loop.
  std::vector<SteadyLeg> idle = legs;
  for (SteadyLeg& l : idle)
    l.water_speed_mps = 0.0;
  EXPECT_EQ(identify_speed_reference(idle, c).legs, 0u);
}

TEST(SpeedReference, EvidenceTurnsWithTheLegs) {
  Sea sea;
  sea.current = toward(0.2, 40.0);
  sea.gnss_sigma_m = 0.3;
  sea.along_sigma_mps = 0.02;
  const auto legs = legs_of(sea, 12, 4);
  const auto base = identify_speed_reference(legs, estimated(legs));
  const auto turned_legs = rotated(legs, 70.0);
  const auto turned = identify_speed_reference(turned_legs, estimated(turned_legs));
  EXPECT_EQ(turned.identified, base.identified);
  EXPECT_NEAR(turned.rms_over_ground_mps, base.rms_over_ground_mps, 1e-9);
  EXPECT_NEAR(turned.rms_through_water_mps, base.rms_through_water_mps, 1e-9);
  EXPECT_NEAR(turned.separation_mps, base.separation_mps, 1e-9);

  const auto c = estimated(legs), tc = estimated(turned_legs);
  const auto a =
      drift_scatter_of(legs, WaterCurrent{c.east_mps, c.north_mps}, SpeedReference::over_ground);
  const auto b = drift_scatter_of(turned_legs, WaterCurrent{tc.east_mps, tc.north_mps},
                                  SpeedReference::over_ground);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(a->along_mps, b->along_mps, 1e-9);
  EXPECT_NEAR(a->cross_mps, b->cross_mps, 1e-9);
}

TEST(DriftScatter, ExactLegsHaveNone) {
  for (const auto loop : {SpeedReference::over_ground, SpeedReference::through_water}) {
    Sea sea;
    sea.current = toward(0.25, 130.0);
    sea.loop = loop;
    const auto legs = legs_of(sea, 8, 5);
    const auto d = drift_scatter_of(legs, sea.current, loop);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->legs, 8u);
    EXPECT_NEAR(d->along_mps, 0.0, 1e-9);
    EXPECT_NEAR(d->cross_mps, 0.0, 1e-9);
    EXPECT_NEAR(d->mean_leg_s, sea.leg_s, 1e-9);
    // The other reference's prediction is wrong along the heading by about c · h, never across.
    const auto other = loop == SpeedReference::over_ground ? SpeedReference::through_water
                                                           : SpeedReference::over_ground;
    const auto wrong = drift_scatter_of(legs, sea.current, other);
    ASSERT_TRUE(wrong);
    EXPECT_GT(wrong->along_mps, 0.1);
    EXPECT_NEAR(wrong->cross_mps, 0.0, 1e-9);
    // Predicting without the current puts all of it into the errors.
    const auto still = drift_scatter_of(legs, std::nullopt, loop);
    ASSERT_TRUE(still);
    EXPECT_GT(std::hypot(still->along_mps, still->cross_mps), 0.15);
  }
}

TEST(DriftScatter, LegsWithAKnownVelocityNoiseGiveThatNoise) {
  Sea sea;
  sea.current = toward(0.2, 250.0);
  sea.along_sigma_mps = 0.06;
  sea.cross_sigma_mps = 0.02;
  const auto legs = legs_of(sea, 800, 6);
  const auto d = drift_scatter_of(legs, sea.current, SpeedReference::over_ground);
  ASSERT_TRUE(d);
  // The RMS of 800 draws is within a few percent of sigma (its relative sd is 1/sqrt(1600)).
  EXPECT_NEAR(d->along_mps, 0.06, 0.006);
  EXPECT_NEAR(d->cross_mps, 0.02, 0.002);
}

TEST(DriftScatter, NeedsThreeLegsAndPoolsByLegs) {
  Sea sea;
  sea.along_sigma_mps = 0.05;
  const auto legs = legs_of(sea, 2, 7);
  EXPECT_FALSE(drift_scatter_of(legs, std::nullopt, SpeedReference::over_ground));
  const DriftScatter a{0.1, 0.02, 1, 10.0}, b{0.0, 0.05, 3, 30.0};
  const auto p = pooled({a, b});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->legs, 4u);
  EXPECT_NEAR(p->along_mps, std::sqrt(0.01 / 4.0), 1e-12);
  EXPECT_NEAR(p->cross_mps, std::sqrt((0.0004 + 3 * 0.0025) / 4.0), 1e-12);
  EXPECT_NEAR(p->mean_leg_s, 25.0, 1e-12);
  EXPECT_FALSE(pooled({}));
}

}  // namespace
