// The pieces that predict a turn with a speed change (u0 -> u1), against
// analytic ground truth.
#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/retimed_turn.hpp"
#include "kinematics/speed_change_table.hpp"
#include "kinematics/speed_response.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/yaw_model.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::circular_arc;
using avk::testing::make_arc_turn;

// A speed step at t1_s: phi = 0 before, 1 after (a ramp of one 1 ms sample).
SpeedResponse step_at(double t1_s) {
  SpeedResponse r;
  r.dt_s = 0.001;
  r.fraction.assign(static_cast<std::size_t>(std::round(t1_s / r.dt_s)) + 1, 0.0);
  r.fraction.push_back(1.0);
  r.tail_tau_s = 1e-6;
  return r;
}

// Analytic position of a right turn from the origin heading north at constant yaw rate r_dps,
// speed u0 until t1 and u1 after: an arc of radius u0/r, then one of radius u1/r.
Point two_arcs(double u0, double u1, double r_dps, double t1, double t) {
  const double r = deg_to_rad(r_dps);
  const auto arc = [&](Point from, double radius, double a0, double a1) {
    return Point{from.x_m + radius * (std::cos(a0) - std::cos(a1)),
                 from.y_m + radius * (std::sin(a1) - std::sin(a0))};
  };
  if (t <= t1) return arc({0.0, 0.0}, u0 / r, 0.0, r * t);
  const Point p1 = arc({0.0, 0.0}, u0 / r, 0.0, r * t1);
  return arc(p1, u1 / r, r * t1, r * t);
}

}  // namespace

TEST(RetimedTurn, WithoutASpeedChangeItIsTheConstantSpeedTurn) {
  // A turn that slows in its arc: the timing is not constant-speed, and must be kept.
  const Polyline arc = circular_arc(3.0, 120.0, 0.05);
  const double length = arc_length_m(arc);
  TurnTiming timing;
  timing.length_m = length;
  for (std::size_t k = 0; k < kTimingStations; ++k) {
    const double f = static_cast<double>(k) / (kTimingStations - 1);
    timing.time_s.push_back(length * f / 1.2 + 2.0 * f * f);
  }
  const RetimedTurn r = retime_turn(arc, timing, 1.2, 1.2, first_order_speed_response(2.0));
  ASSERT_EQ(r.trajectory.size(), arc.size());
  for (std::size_t i = 0; i < arc.size(); ++i)
    EXPECT_LT(distance_m(r.trajectory[i], arc[i]), 1e-9) << i;
  EXPECT_NEAR(r.timing.length_m, length, 1e-9);
  for (std::size_t k = 0; k < kTimingStations; ++k)
    EXPECT_NEAR(r.timing.time_s[k], timing.time_s[k], 1e-3) << k;
}

TEST(RetimedTurn, ConstantYawRateWithASpeedStepIsTwoArcs) {
  const double u0 = 1.5, u1 = 0.75, r_dps = 15.0, t1 = 2.0;
  // The constant-speed turn: radius u0 / r at constant speed u0, 150 deg in 10 s.
  const double radius = u0 / deg_to_rad(r_dps);
  const Polyline arc = circular_arc(radius, 150.0, 0.01);
  const RetimedTurn r = retime_turn(arc, std::nullopt, u0, u1, step_at(t1));
  const double t_end = 150.0 / r_dps;
  const Point truth = two_arcs(u0, u1, r_dps, t1, t_end);
  EXPECT_LT(distance_m(r.trajectory.back(), truth), 0.02)
      << r.trajectory.back().x_m << "," << r.trajectory.back().y_m << " vs " << truth.x_m << ","
      << truth.y_m;
  // Every vertex lies on the analytic path at its time.
  double worst = 0.0;
  for (std::size_t i = 0; i < r.trajectory.size(); ++i)
    worst = std::max(worst, distance_m(r.trajectory[i], two_arcs(u0, u1, r_dps, t1, r.time_s[i])));
  EXPECT_LT(worst, 0.02);
  // The slower second arc makes the turn tighter: it reaches less far north (the advance at
  // 90 deg: R0 sin 30 + R1 (1 - sin 30)) and less far east.
  const RetimedTurn same = retime_turn(arc, std::nullopt, u0, u0, step_at(t1));
  const auto max_y = [](const Polyline& p) {
    double m = 0.0;
    for (const auto& q : p)
      m = std::max(m, q.y_m);
    return m;
  };
  const double r0 = u0 / deg_to_rad(r_dps), r1 = u1 / deg_to_rad(r_dps);
  EXPECT_NEAR(max_y(r.trajectory), r0 * 0.5 + r1 * 0.5, 0.02);
  EXPECT_NEAR(max_y(same.trajectory), r0, 0.02);
  EXPECT_LT(r.transfer_m, same.transfer_m - 1.0);
  EXPECT_NEAR(r.timing.time_s.back(), t_end, 1e-4);
}

TEST(RetimedTurn, RefusesSpeedsThatAreNotPositive) {
  const Polyline arc = circular_arc(3.0, 90.0, 0.1);
  EXPECT_THROW(retime_turn(arc, std::nullopt, 0.0, 1.0, step_at(1.0)), std::invalid_argument);
  EXPECT_THROW(retime_turn(arc, std::nullopt, 1.0, -1.0, step_at(1.0)), std::invalid_argument);
  EXPECT_THROW(retime_turn(Polyline{{0, 0}}, std::nullopt, 1.0, 1.0, step_at(1.0)),
               std::invalid_argument);
}

TEST(SpeedResponse, TheSpeedModelIsAFirstOrderLag) {
  YawModel m;
  m.rate_hz = 4.0;
  m.speed = SpeedModel{0.1, 0.0, 0.0};
  const auto r = speed_response_of_model(m);
  ASSERT_TRUE(r);
  for (int k : {0, 1, 4, 10, 40})
    EXPECT_NEAR(r->fraction_at(k * 0.25), 1.0 - std::pow(0.9, k), 1e-9) << k;
  EXPECT_NEAR(r->speed_at_mps(1.0, 1.5, 0.75), 1.5 - 0.75 * (1.0 - std::pow(0.9, 4)), 1e-9);
  m.speed.reset();
  EXPECT_FALSE(speed_response_of_model(m));
}

TEST(SpeedResponse, MeasuredFromTurnsRecoversTheirProfile) {
  // Turns whose recorded speed falls from u0 to u1 as a known first-order lag (tau 3 s).
  const double tau = 3.0;
  std::vector<TurnSequence> turns;
  for (const auto& [u0, u1] : {std::pair{1.5, 0.75}, std::pair{1.0, 0.5}, std::pair{0.6, 1.2}}) {
    ArcTurnSpec spec;
    spec.speed_mps = u0;
    spec.dheading_deg = 90.0;
    TurnSequence t = make_arc_turn(spec);
    std::vector<TurnSample> s = t.samples();
    for (auto& p : s)
      p.speed_mps = u0 + (u1 - u0) * (1.0 - std::exp(-(p.t_s - s.front().t_s) / tau));
    TurnMeta m = t.meta();
    m.speed_after_mps = u1;
    turns.emplace_back(m, s);
  }
  turns.push_back(make_arc_turn({}));  // constant speed: not used
  const auto r = measured_speed_response(turns);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->n_turns, 3u);
  for (double t : {0.5, 1.0, 3.0, 5.0, 12.0})
    EXPECT_NEAR(r->fraction_at(t), 1.0 - std::exp(-t / tau), 0.01) << t;
  EXPECT_NEAR(r->tail_tau_s, tau, 0.1);
  EXPECT_FALSE(measured_speed_response({make_arc_turn({})}));
}

TEST(SpeedChangeTable, HoldsCollectedPairsOnlyAndTheCktLeavesThemOut) {
  std::vector<TurnSequence> turns;
  for (double d : {45.0, 90.0}) {
    for (unsigned seed : {1u, 2u}) {
      ArcTurnSpec spec;
      spec.speed_mps = 1.5;
      spec.dheading_deg = seed == 1 ? d : -d;
      spec.radius_m = d == 45.0 ? 4.0 : 3.0;
      spec.position_noise_m = 0.01;
      spec.seed = seed;
      TurnSequence t = make_arc_turn(spec);
      t.meta().speed_after_mps = 0.75;
      turns.push_back(t);
      spec.radius_m = 6.0;  // the constant-speed turns at 1.5 m/s are wider
      turns.push_back(make_arc_turn(spec));
    }
  }
  CktBuildReport rep;
  const Ckt ckt = Ckt::build(turns, {}, std::nullopt, &rep);
  EXPECT_EQ(rep.turns_used, 4u);
  EXPECT_EQ(rep.turns_speed_change, 4u);
  const SpeedChangeTable table = SpeedChangeTable::build(turns);
  ASSERT_EQ(table.pairs().size(), 1u);
  EXPECT_EQ(table.pairs()[0].from_mps, 1.5);
  EXPECT_EQ(table.pairs()[0].to_mps, 0.75);
  const auto exact = table.query(1.5, 0.75, 90.0);
  ASSERT_TRUE(exact);
  EXPECT_TRUE(exact->exact_cell);
  EXPECT_NEAR(exact->advance_m, 2.0 + 3.0, 0.05);
  EXPECT_NEAR(exact->transfer_m, 3.0, 0.05);
  // Between its heading changes, interpolated like Ckt::query; left turns reflected.
  const auto between = table.query(1.5, 0.74, -60.0);
  ASSERT_TRUE(between);
  EXPECT_FALSE(between->exact_cell);
  EXPECT_LT(between->trajectory.back().x_m, 0.0);
  // Anywhere else: no answer.
  EXPECT_FALSE(table.query(1.5, 0.5, 90.0));
  EXPECT_FALSE(table.query(1.0, 0.75, 90.0));
  EXPECT_FALSE(table.query(1.5, 1.5, 90.0));
  EXPECT_GT(ckt.query(1.5, 90.0).transfer_m, exact->transfer_m + 2.0);
}

TEST(SpeedChangeTurnJson, RoundTripsTheSpeedAfterAndOldDocumentsLoad) {
  TurnSequence t = make_arc_turn({});
  const std::string plain = to_json_string(t);
  EXPECT_EQ(plain.find("speed_after_mps"), std::string::npos);
  EXPECT_FALSE(parse_turn_json(plain).meta().speed_after_mps);
  t.meta().speed_after_mps = 0.5;
  const TurnSequence back = parse_turn_json(to_json_string(t));
  EXPECT_EQ(back.meta().speed_after_mps, 0.5);
  auto j = to_json(t);
  j["speed_after_mps"] = -1.0;
  EXPECT_THROW(parse_turn_json(j.dump()), ParseError);
}

TEST(SpeedChangeYawModel, TheSpeedModelFollowsTheSteppedCommand) {
  YawModel m;
  m.history = 1;
  m.rate_hz = 4.0;
  m.error_coeffs = {0.1};
  m.heading_coeffs = {0.5};
  m.speed = SpeedModel{0.2, 0.0, 0.0};
  const Polyline same = predict_normalized_turn(m, 1.5, 90.0, 0.0, 0.0, 200, true);
  const Polyline slower = predict_normalized_turn(m, 1.5, 90.0, 0.0, 0.0, 200, true, 0.0, 0.75);
  ASSERT_EQ(same.size(), slower.size());
  // The first step is at u0, the last ones at u1.
  const auto step = [](const Polyline& p, std::size_t i) { return distance_m(p[i], p[i + 1]); };
  EXPECT_NEAR(step(slower, 0), 1.5 * 0.25, 1e-9);
  EXPECT_NEAR(step(slower, slower.size() - 2), 0.75 * 0.25, 1e-6);
  EXPECT_NEAR(step(same, same.size() - 2), 1.5 * 0.25, 1e-6);
  EXPECT_LT(arc_length_m(slower), arc_length_m(same) - 10.0);
}

TEST(RetimedTurn, ACktAnswerKeepsItsEndOfTurnPointReTimed) {
  // A 90 deg arc of radius 4 at 1 m/s that runs on 3 m along the goal heading; the turn ended at
  // the end of the arc (advance 4, transfer 4).
  const double radius = 4.0;
  Polyline arc = circular_arc(radius, 90.0, 0.01);
  arc.push_back({arc.back().x_m + 3.0, arc.back().y_m});
  TurnPrediction p;
  p.dheading_deg = 90.0;
  p.trajectory = arc;
  p.advance_m = radius;
  p.transfer_m = radius;
  const RetimedTurn same = retime_turn(p, 1.0, 1.0, step_at(1.0));
  EXPECT_NEAR(same.advance_m, radius, 1e-6);
  EXPECT_NEAR(same.transfer_m, radius, 1e-6);
  // Halving the speed at t = 0 halves every length: the end of the turn at (2, 2).
  const RetimedTurn half = retime_turn(p, 1.0, 0.5, step_at(0.0));
  EXPECT_NEAR(half.advance_m, 2.0, 0.01);
  EXPECT_NEAR(half.transfer_m, 2.0, 0.01);
  // A left turn likewise, transfer positive towards the turn.
  p.dheading_deg = -90.0;
  p.trajectory = reflect_x(arc);
  const RetimedTurn left = retime_turn(p, 1.0, 0.5, step_at(0.0));
  EXPECT_NEAR(left.transfer_m, 2.0, 0.01);
  EXPECT_LT(left.trajectory.back().x_m, 0.0);
}
