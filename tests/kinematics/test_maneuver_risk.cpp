// The position band, the risk of a close approach, the choice by risk and COLREGS situations,
// and the drift of a vehicle holding its speed over ground: analytic cases and invariances.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "kinematics/approach_risk.hpp"
#include "kinematics/colregs.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/maneuver_choice.hpp"
#include "kinematics/position_band.hpp"
#include "kinematics/water_frame.hpp"

namespace avk::kinematics {
namespace {

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

TimedPath straight(double heading_deg, double speed_mps, double horizon_s, double step_s = 1.0) {
  TimedPath p;
  for (double t = 0.0; t <= horizon_s + 1e-9; t += step_s) {
    const Point d = rotate_by_heading({0.0, speed_mps * t}, heading_deg);
    p.push_back({t, d.x_m, d.y_m});
  }
  return p;
}

Point rotated(Point p, double deg) {
  return rotate_by_heading(p, deg);
}

// ---- over ground --------------------------------------------------------------------------

TEST(OverGround, ScaleMakesTheSpeedGoodOverGround) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ang(0.0, 360.0), sp(0.3, 2.0), cur(0.0, 0.25);
  for (int i = 0; i < 200; ++i) {
    const Point u = rotate_by_heading({0.0, sp(rng)}, ang(rng));
    const Point c = rotate_by_heading({0.0, cur(rng)}, ang(rng));
    const double k = over_ground_scale(u, c);
    EXPECT_NEAR(std::hypot(k * u.x_m + c.x_m, k * u.y_m + c.y_m), std::hypot(u.x_m, u.y_m), 1e-9);
  }
  // With and against the current: k = 1 -+ |c|/|u|.
  EXPECT_NEAR(over_ground_scale({0.0, 1.0}, {0.0, 0.2}), 0.8, 1e-12);
  EXPECT_NEAR(over_ground_scale({0.0, 1.0}, {0.0, -0.2}), 1.2, 1e-12);
  EXPECT_DOUBLE_EQ(over_ground_scale({0.0, 1.0}, {0.0, 0.0}), 1.0);
  // A current the loop cannot beat saturates at the bound.
  EXPECT_DOUBLE_EQ(over_ground_scale({0.0, 1.0}, {0.0, -3.0}), kMaxOverGroundScale);
}

TEST(OverGround, StraightLegInACrossCurrentEachReference) {
  const TimedPath water = straight(0.0, 1.0, 60.0);
  const Point c{0.3, 0.0};
  // Over ground: the speed over ground is the commanded 1 m/s, the track sets to the east.
  const TimedPath og = retimed_over_ground(water, c);
  const double k = std::sqrt(1.0 - 0.09);
  for (std::size_t i = 1; i < og.size(); ++i) {
    const double dt = og[i].t_s - og[i - 1].t_s;
    EXPECT_NEAR(dt, 1.0 / k, 1e-9);
    EXPECT_NEAR(std::hypot(og[i].x_m - og[i - 1].x_m, og[i].y_m - og[i - 1].y_m) / dt, 1.0, 1e-9);
  }
  EXPECT_NEAR(og.back().x_m, 0.3 * og.back().t_s, 1e-9);
  // Through the water: carried by c·t, speed over ground sqrt(1 + 0.09).
  const TimedPath tw = drifted(water, c);
  EXPECT_NEAR(tw.back().x_m, 0.3 * 60.0, 1e-9);
  EXPECT_NEAR(tw.back().y_m, 60.0, 1e-9);
}

TEST(OverGround, ArcInACurrentKeepsEachSegmentsSpeedAndRotatesWithTheFrame) {
  // A quarter circle of radius 10 m at 1 m/s (water), then its rotation.
  TimedPath arc;
  for (int i = 0; i <= 30; ++i) {
    const double a = (std::numbers::pi / 2.0) * i / 30.0;
    arc.push_back({10.0 * a, 10.0 - 10.0 * std::cos(a), 10.0 * std::sin(a)});
  }
  const Point c{-0.15, 0.2};
  const TimedPath og = retimed_over_ground(arc, c);
  for (std::size_t i = 1; i < og.size(); ++i) {
    const double dt = og[i].t_s - og[i - 1].t_s;
    const double water_speed =
        std::hypot(arc[i].x_m - arc[i - 1].x_m, arc[i].y_m - arc[i - 1].y_m) /
        (arc[i].t_s - arc[i - 1].t_s);
    EXPECT_NEAR(std::hypot(og[i].x_m - og[i - 1].x_m, og[i].y_m - og[i - 1].y_m) / dt, water_speed,
                1e-9);
  }
  for (const double rot : {37.0, 145.0, -90.0}) {
    TimedPath r;
    for (const auto& p : arc) {
      const Point q = rotated({p.x_m, p.y_m}, rot);
      r.push_back({p.t_s, q.x_m, q.y_m});
    }
    const TimedPath ogr = retimed_over_ground(r, rotated(c, rot));
    for (std::size_t i = 0; i < og.size(); ++i) {
      const Point q = rotated({og[i].x_m, og[i].y_m}, rot);
      EXPECT_NEAR(ogr[i].x_m, q.x_m, 1e-9);
      EXPECT_NEAR(ogr[i].y_m, q.y_m, 1e-9);
      EXPECT_NEAR(ogr[i].t_s, og[i].t_s, 1e-9);
    }
  }
}

TEST(OverGround, PlacedPredictionReachesTheHorizonWithItsValues) {
  PredictedManeuver m;
  m.dheading_deg = 0.0;
  m.speed_mps = 1.0;
  m.path = {{0.0, 0.0, 0.0}, {10.0, 0.0, 10.0}};
  m.along_sd_m = {0.0, 1.0};
  m.cross_sd_m = {0.0, 2.0};
  m.turn_points = 2;
  for (const Point c : {Point{0.0, 0.3}, Point{0.0, -0.3}, Point{0.2, 0.0}}) {
    const PredictedManeuver g =
        placed_over_ground(m, {5.0, 5.0, 90.0}, WaterCurrent{c.x_m, c.y_m}, true, 60.0);
    ASSERT_EQ(g.path.size(), g.along_sd_m.size());
    ASSERT_EQ(g.path.size(), g.cross_sd_m.size());
    EXPECT_NEAR(g.path.back().t_s, 60.0, 1e-9);
    // Held east at 1 m/s over ground the whole time.
    EXPECT_NEAR(std::hypot(g.path.back().x_m - 5.0, g.path.back().y_m - 5.0), 60.0, 1e-6);
    EXPECT_DOUBLE_EQ(g.cross_sd_m.back(), 2.0);
  }
}

// ---- the band ------------------------------------------------------------------------------

TEST(PositionBand, EachSourceGrowsAsItShould) {
  const TimedPath p = straight(0.0, 1.0, 100.0, 10.0);
  BandSources none;
  for (const auto& c : position_band(p, {}, {}, 1, none))
    EXPECT_EQ(c, (Covariance2{0.0, 0.0, 0.0}));
  BandSources scatter;
  scatter.scatter = {0.1, 0.02};
  const auto b = position_band(p, {}, {}, 1, scatter);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double t = p[i].t_s;
    EXPECT_NEAR(b[i][2], 0.01 * t * t, 1e-9);    // along = north
    EXPECT_NEAR(b[i][0], 0.0004 * t * t, 1e-9);  // across = east
    EXPECT_NEAR(b[i][1], 0.0, 1e-9);
  }
  BandSources floor;
  floor.position_sd_m = 0.3;
  for (const auto& c : position_band(p, {}, {}, 1, floor))
    EXPECT_EQ(c, (Covariance2{0.09, 0.0, 0.09}));
  BandSources current;
  current.current_covariance_m2ps2 = {0.0004, 0.0001, 0.0009};
  const auto cc = position_band(p, {}, {}, 1, current);
  EXPECT_NEAR(cc.back()[0], 0.0004 * 1e4, 1e-9);
  EXPECT_NEAR(cc.back()[1], 0.0001 * 1e4, 1e-9);
  EXPECT_NEAR(cc.back()[2], 0.0009 * 1e4, 1e-9);
}

TEST(PositionBand, TurnSpreadIsHeldAndGrowthStartsAtTheTurnsEnd) {
  const TimedPath p = straight(90.0, 1.0, 50.0, 10.0);  // 6 points, east
  const std::vector<double> along{0, 1, 2, 3, 9, 9}, cross{0, 0.5, 1, 1.5, 9, 9};
  BandSources s;
  s.scatter = {0.1, 0.1};
  const auto b = position_band(p, along, cross, 4, s);  // the turn: points 0..3, ends at t = 30
  // East path: along = xx, across = yy.
  EXPECT_NEAR(b[3][0], 9.0, 1e-9);
  EXPECT_NEAR(b[3][2], 2.25, 1e-9);
  EXPECT_NEAR(b[5][0], 9.0 + 4.0, 1e-9);  // held 3 m, plus 0.1 m/s for 20 s
  EXPECT_NEAR(b[5][2], 2.25 + 4.0, 1e-9);
}

TEST(PositionBand, RotatesWithThePath) {
  const std::vector<double> along{0, 1, 2, 2}, cross{0, 0.3, 0.6, 0.6};
  BandSources s;
  s.scatter = {0.05, 0.2};
  const auto north = position_band(straight(0.0, 1.0, 30.0, 10.0), along, cross, 3, s);
  const auto rot = position_band(straight(60.0, 1.0, 30.0, 10.0), along, cross, 3, s);
  for (std::size_t i = 0; i < north.size(); ++i) {
    // The variance along a direction turns with the path.
    for (const double dir : {0.0, 45.0, 90.0}) {
      const Point n = rotate_by_heading({0.0, 1.0}, dir),
                  r = rotate_by_heading({0.0, 1.0}, dir + 60.0);
      EXPECT_NEAR(variance_along(north[i], n), variance_along(rot[i], r), 1e-9);
    }
  }
}

TEST(PositionBand, EllipseAndMahalanobisAgree) {
  EXPECT_NEAR(band_radius_factor(0.9), std::sqrt(-2.0 * std::log(0.1)), 1e-12);
  const Covariance2 c{4.0, 0.0, 1.0};  // sd 2 east, 1 north
  const BandEllipse e = band_ellipse(c, 0.9);
  const double k = band_radius_factor(0.9);
  EXPECT_NEAR(e.major_m, 2.0 * k, 1e-9);
  EXPECT_NEAR(e.minor_m, k, 1e-9);
  EXPECT_NEAR(e.major_axis_deg, 90.0, 1e-9);
  EXPECT_NEAR(mahalanobis2(c, {2.0 * k, 0.0}), k * k, 1e-4);
  EXPECT_NEAR(mahalanobis2(c, {0.0, k}), k * k, 1e-4);
  // A share of draws inside the band is the share.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> z;
  int inside = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    inside += mahalanobis2(c, {2.0 * z(rng), z(rng)}) <= k * k ? 1 : 0;
  EXPECT_NEAR(static_cast<double>(inside) / n, 0.9, 0.01);
  EXPECT_THROW(band_radius_factor(1.0), std::invalid_argument);
}

// ---- the risk ------------------------------------------------------------------------------

TEST(ApproachRisk, ExactApproachIsAStep) {
  const TimedPath own = straight(0.0, 1.0, 60.0);
  const std::vector<Covariance2> zero(own.size(), Covariance2{0.0, 0.0, 0.0});
  EXPECT_EQ(approach_risk(own, zero, Contact{8.0, 30.0, 0.0, 0.0}, 10.0), 1.0);
  EXPECT_EQ(approach_risk(own, zero, Contact{12.0, 30.0, 0.0, 0.0}, 10.0), 0.0);
}

TEST(ApproachRisk, CrossingWithAnIsotropicBandIsTheNormalMissProbability) {
  // Own north at 1 m/s, contact crossing west at 1 m/s passing 6 m ahead of the own path at
  // t = 30 s; the own position has sd 4 m in every direction all the way.
  const TimedPath own = straight(0.0, 1.0, 80.0, 0.5);
  const double sd = 4.0;
  const std::vector<Covariance2> band(own.size(), Covariance2{sd * sd, 0.0, sd * sd});
  const Contact c{30.0, 36.0, 270.0, 1.0};
  const double d = 10.0;
  const Approach a = closest_approach(own, c);
  const double m = a.distance_m;
  const double expected = normal_cdf((d - m) / sd) - normal_cdf((-d - m) / sd);
  const double risk = approach_risk(own, band, c, d);
  EXPECT_NEAR(risk, expected, 1e-3);
  // Monte Carlo: a constant offset of the own path.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> z(0.0, sd);
  int hits = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double ex = z(rng), ey = z(rng);
    TimedPath shifted = own;
    for (auto& p : shifted)
      p.x_m += ex, p.y_m += ey;
    hits += closest_approach(shifted, c).distance_m < d ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(hits) / n, risk, 0.03);
}

TEST(ApproachRisk, ContactPositionUncertaintyCountsLikeTheOwnBand) {
  const TimedPath own = straight(0.0, 1.0, 80.0, 0.5);
  const std::vector<Covariance2> band(own.size(), Covariance2{9.0, 0.0, 9.0});
  const std::vector<Covariance2> zero(own.size(), Covariance2{0.0, 0.0, 0.0});
  Contact c{14.0, 40.0, 180.0, 0.5};
  const double own_only = approach_risk(own, band, c, 10.0);
  c.position_sd_m = 3.0;
  EXPECT_NEAR(approach_risk(own, zero, c, 10.0), own_only, 1e-9);
  // Uncertainty in the contact's course widens a risk that was nil.
  Contact far{25.0, 40.0, 180.0, 1.0};
  EXPECT_LT(approach_risk(own, zero, far, 10.0), 1e-9);
  far.course_sd_deg = 30.0;
  EXPECT_GT(approach_risk(own, zero, far, 10.0), 0.01);
}

TEST(ApproachRisk, InvariantUnderRotationAndTranslation) {
  TimedPath own;
  for (int i = 0; i <= 60; ++i) {
    const double a = i * 0.05;
    own.push_back({static_cast<double>(i), 20.0 - 20.0 * std::cos(a), 20.0 * std::sin(a)});
  }
  BandSources s;
  s.scatter = {0.1, 0.05};
  s.current_covariance_m2ps2 = {0.001, 0.0, 0.002};
  const Contact c{30.0, 30.0, 250.0, 0.8, 1.0, 5.0, 0.1};
  const double r0 = approach_risk(own, position_band(own, {}, {}, 1, s), c, 10.0);
  EXPECT_GT(r0, 0.0);
  for (const double rot : {30.0, 200.0}) {
    TimedPath o2;
    for (const auto& p : own) {
      const Point q = rotated({p.x_m, p.y_m}, rot);
      o2.push_back({p.t_s, q.x_m + 100.0, q.y_m - 50.0});
    }
    BandSources s2 = s;
    // The current's covariance rotated: R C R'.
    const double th = -rot * std::numbers::pi / 180.0;
    const double cs = std::cos(th), sn = std::sin(th);
    const Covariance2 C = s.current_covariance_m2ps2;
    s2.current_covariance_m2ps2 = {cs * cs * C[0] - 2 * cs * sn * C[1] + sn * sn * C[2],
                                   cs * sn * C[0] + (cs * cs - sn * sn) * C[1] - cs * sn * C[2],
                                   sn * sn * C[0] + 2 * cs * sn * C[1] + cs * cs * C[2]};
    const Point cp = rotated({c.x_m, c.y_m}, rot);
    Contact c2 = c;
    c2.x_m = cp.x_m + 100.0, c2.y_m = cp.y_m - 50.0, c2.course_deg = c.course_deg + rot;
    EXPECT_NEAR(approach_risk(o2, position_band(o2, {}, {}, 1, s2), c2, 10.0), r0, 1e-9);
  }
}

// ---- COLREGS and the choice ------------------------------------------------------------------

TEST(Colregs, SituationsAndTheirInvariance) {
  for (const double h : {0.0, 77.0, 250.0}) {
    const Pose own{10.0, -5.0, h};
    const auto at = [&](double bearing_rel, double range, double course_rel, double speed) {
      const Point p = rotate_by_heading({0.0, range}, h + bearing_rel);
      return Contact{own.x_m + p.x_m, own.y_m + p.y_m, h + course_rel, speed};
    };
    EXPECT_EQ(classify_encounter(own, 1.0, at(2.0, 80.0, 181.0, 1.0)), Situation::head_on);
    EXPECT_EQ(classify_encounter(own, 1.0, at(45.0, 80.0, 270.0, 1.0)),
              Situation::crossing_give_way);
    EXPECT_EQ(classify_encounter(own, 1.0, at(-45.0, 80.0, 90.0, 1.0)),
              Situation::crossing_stand_on);
    EXPECT_EQ(classify_encounter(own, 1.5, at(0.0, 40.0, 0.0, 0.5)), Situation::overtaking);
    EXPECT_EQ(classify_encounter(own, 0.5, at(180.0, 40.0, 0.0, 1.5)), Situation::overtaken);
    EXPECT_EQ(classify_encounter(own, 1.0, at(90.0, 40.0, 90.0, 1.0)), Situation::none);  // opening
  }
  EXPECT_TRUE(asks_starboard(Situation::head_on));
  EXPECT_TRUE(asks_starboard(Situation::crossing_give_way));
  EXPECT_FALSE(asks_starboard(Situation::crossing_stand_on));
  EXPECT_STREQ(rule_of(Situation::head_on), "14");
}

CandidateEvaluation with_risk(double d, double risk, std::size_t contacts = 1) {
  CandidateEvaluation c;
  c.dheading_deg = d;
  c.risk = risk;
  c.min_cpa_m = 20.0;
  c.contacts.resize(contacts);
  for (auto& a : c.contacts)
    a.risk = risk;
  return c;
}

TEST(ManeuverChoice, SmallestTurnWithinTheLimitElseTheLeastRisky) {
  ManeuverProblem p;
  p.standoff_m = 10.0;
  p.contacts = {Contact{0.0, 50.0, 180.0, 1.0}};
  const std::vector<CandidateEvaluation> cs{with_risk(-20, 0.01), with_risk(-10, 0.04),
                                            with_risk(0, 0.5), with_risk(10, 0.06),
                                            with_risk(20, 0.02)};
  const ManeuverChoice c = choose_by_risk(p, 1.0, cs, {0.05, false});
  ASSERT_TRUE(c.index);
  EXPECT_EQ(cs[*c.index].dheading_deg, -10.0);
  EXPECT_TRUE(c.within_limit);
  EXPECT_NEAR(c.margin_m, 10.0, 1e-12);
  // Equal |dheading| within the limit: starboard.
  const std::vector<CandidateEvaluation> tie{with_risk(-10, 0.01), with_risk(0, 0.3),
                                             with_risk(10, 0.02)};
  EXPECT_EQ(tie[*choose_by_risk(p, 1.0, tie, {}).index].dheading_deg, 10.0);
  // Keep course when its own risk is within the limit.
  const std::vector<CandidateEvaluation> keep{with_risk(-10, 0.0), with_risk(0, 0.049),
                                              with_risk(10, 0.0)};
  EXPECT_EQ(keep[*choose_by_risk(p, 1.0, keep, {}).index].dheading_deg, 0.0);
  // None within the limit: the least risky, said.
  const std::vector<CandidateEvaluation> none{with_risk(-10, 0.3), with_risk(0, 0.9),
                                              with_risk(30, 0.2)};
  const ManeuverChoice n = choose_by_risk(p, 1.0, none, {});
  EXPECT_EQ(none[*n.index].dheading_deg, 30.0);
  EXPECT_FALSE(n.within_limit);
  EXPECT_THROW(choose_by_risk(p, 1.0, cs, {1.5, false}), std::invalid_argument);
}

TEST(ManeuverChoice, HeadOnKeepsToStarboardAndSaysWhichRule) {
  ManeuverProblem p;
  p.own = {0.0, 0.0, 0.0};
  p.contacts = {Contact{1.0, 60.0, 180.0, 1.0}};  // dead ahead, reciprocal
  const std::vector<CandidateEvaluation> cs{with_risk(-10, 0.01), with_risk(0, 0.8),
                                            with_risk(10, 0.2), with_risk(20, 0.03)};
  const ManeuverChoice plain = choose_by_risk(p, 1.0, cs, {0.05, false});
  EXPECT_EQ(cs[*plain.index].dheading_deg, -10.0);
  EXPECT_TRUE(plain.colregs_rule.empty());
  const ManeuverChoice rules = choose_by_risk(p, 1.0, cs, {0.05, true});
  EXPECT_EQ(cs[*rules.index].dheading_deg, 20.0);
  EXPECT_EQ(rules.colregs_rule, "14");
  ASSERT_EQ(rules.situations.size(), 1u);
  EXPECT_EQ(rules.situations[0], Situation::head_on);
  // No starboard turn within the limit: either side, and the answer says the rule was not kept.
  const std::vector<CandidateEvaluation> port_only{with_risk(-10, 0.01), with_risk(0, 0.8),
                                                   with_risk(10, 0.2)};
  const ManeuverChoice fallback = choose_by_risk(p, 1.0, port_only, {0.05, true});
  EXPECT_EQ(port_only[*fallback.index].dheading_deg, -10.0);
  EXPECT_TRUE(fallback.colregs_rule.empty());
  // Crossing from port: the contact gives way; no starboard preference.
  p.contacts = {Contact{-40.0, 40.0, 90.0, 1.0}};
  const ManeuverChoice stand_on = choose_by_risk(p, 1.0, cs, {0.05, true});
  EXPECT_EQ(cs[*stand_on.index].dheading_deg, -10.0);
  EXPECT_EQ(stand_on.situations[0], Situation::crossing_stand_on);
}

}  // namespace
}  // namespace avk::kinematics
