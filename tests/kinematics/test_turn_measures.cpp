#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_sequence.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

ArcTurnSpec arc(double dheading_deg, double lead_in_m, double radius_m, double speed_mps = 1.0,
                double dt_s = 0.1) {
  ArcTurnSpec spec;
  spec.dheading_deg = dheading_deg;
  spec.lead_in_m = lead_in_m;
  spec.radius_m = radius_m;
  spec.speed_mps = speed_mps;
  spec.dt_s = dt_s;
  spec.start = {100.0, -50.0, 37.0};
  return spec;
}

void expect_same(const std::optional<double>& a, const std::optional<double>& b, const char* what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_NEAR(*a, *b, 1e-9) << what;
  }
}

}  // namespace

TEST(TurnMeasures, AdvanceAndTransferOfArcTurnsMatchTheGeometry) {
  int cases = 0;
  for (double dpsi_deg = 10.0; dpsi_deg <= 170.0; dpsi_deg += 20.0) {
    for (double lead_m : {0.5, 2.0, 5.0}) {
      for (double radius_m : {1.5, 3.0, 8.0}) {
        for (double sign : {1.0, -1.0}) {
          const auto turn = make_arc_turn(arc(sign * dpsi_deg, lead_m, radius_m, 1.0, 0.25));
          const double dpsi = deg_to_rad(dpsi_deg);
          const double advance_m = lead_m + radius_m * std::sin(dpsi);
          const double transfer_m = radius_m * (1.0 - std::cos(dpsi));
          const AdvanceTransfer at = advance_transfer(turn);
          EXPECT_NEAR(at.advance_m, advance_m, 1e-9) << dpsi_deg << " " << lead_m << " " << sign;
          EXPECT_NEAR(at.transfer_m, transfer_m, 1e-9) << dpsi_deg << " " << lead_m << " " << sign;
          const AdvanceTransfer from_points = advance_transfer(turn.normalized().points());
          EXPECT_NEAR(from_points.advance_m, advance_m, 1e-9);
          EXPECT_NEAR(from_points.transfer_m, transfer_m, 1e-9);
          const TurnMeasures m = measure_turn(turn);
          EXPECT_NEAR(m.at_end.advance_m, advance_m, 1e-9);
          EXPECT_NEAR(m.at_end.transfer_m, transfer_m, 1e-9);
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 9 * 3 * 3 * 2);
}

TEST(TurnMeasures, NinetyDegreeValuesOfAnArcTurn) {
  const double lead_m = 2.0, radius_m = 3.0, speed_mps = 1.5;
  const TurnMeasures m = measure_turn(make_arc_turn(arc(120.0, lead_m, radius_m, speed_mps)));
  ASSERT_TRUE(m.advance_90_m && m.transfer_90_m && m.time_to_90_s);
  // Positions between samples are interpolated on the chord: a few mm at these sample spacings.
  EXPECT_NEAR(*m.advance_90_m, lead_m + radius_m, 3e-3);
  EXPECT_NEAR(*m.transfer_90_m, radius_m, 3e-3);
  EXPECT_NEAR(*m.time_to_90_s, (lead_m + radius_m * std::numbers::pi / 2.0) / speed_mps, 1e-6);
  EXPECT_FALSE(m.tactical_diameter_m);
  EXPECT_FALSE(m.time_to_180_s);
}

TEST(TurnMeasures, TacticalDiameterOfAHalfTurnIsTwiceTheRadius) {
  const double lead_m = 1.0, radius_m = 2.5, speed_mps = 0.8;
  for (double dpsi_deg : {180.0, 200.0}) {
    const TurnMeasures m = measure_turn(make_arc_turn(arc(dpsi_deg, lead_m, radius_m, speed_mps)));
    ASSERT_TRUE(m.tactical_diameter_m) << dpsi_deg;
    ASSERT_TRUE(m.time_to_180_s) << dpsi_deg;
    EXPECT_NEAR(*m.tactical_diameter_m, 2.0 * radius_m, 3e-3) << dpsi_deg;
    // The generator stamps a last sample that falls between ticks with the next tick, so a turn
    // ending exactly at 180 degrees reaches it up to one dt late.
    const double dt_tolerance_s = dpsi_deg == 180.0 ? 0.1 : 1e-6;
    EXPECT_NEAR(*m.time_to_180_s, (lead_m + radius_m * std::numbers::pi) / speed_mps,
                dt_tolerance_s);
  }
}

TEST(TurnMeasures, SteadyTurningRadiusOfAConstantSpeedArc) {
  for (double radius_m : {2.0, 4.0, 10.0}) {
    const double speed_mps = 1.2;
    const TurnMeasures m = measure_turn(make_arc_turn(arc(150.0, 2.3, radius_m, speed_mps, 0.25)));
    ASSERT_TRUE(m.steady_turning_radius_m) << radius_m;
    EXPECT_NEAR(*m.steady_turning_radius_m / radius_m, 1.0, 0.03) << radius_m;
    ASSERT_TRUE(m.steady_yaw_rate_dps);
    EXPECT_NEAR(*m.steady_yaw_rate_dps / rad_to_deg(speed_mps / radius_m), 1.0, 0.03);
  }
}

TEST(TurnMeasures, SteadyTurningRadiusSurvivesHeadingNoise) {
  // 0.5 deg heading noise at 4 Hz is +-3 deg/s on a 14 deg/s yaw rate.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    ArcTurnSpec spec = arc(150.0, 2.0, 4.0, 1.0, 0.25);
    spec.heading_noise_deg = 0.5;
    spec.seed = seed;
    const TurnMeasures m = measure_turn(make_arc_turn(spec));
    ASSERT_TRUE(m.steady_turning_radius_m) << seed;
    EXPECT_NEAR(*m.steady_turning_radius_m / 4.0, 1.0, 0.05) << seed;
  }
}

TEST(TurnMeasures, AlternatingYawRateIsNeverSteady) {
  // Yaw rate alternating 5 and 20 deg/s: no three consecutive intervals agree within 10 %.
  TurnMeta meta;
  meta.goal_dheading_deg = 90.0;
  std::vector<TurnSample> samples;
  double heading_deg = 0.0;
  for (int k = 0; k <= 10; ++k) {
    const double a = deg_to_rad(heading_deg);
    const Point p = samples.empty()
                        ? Point{}
                        : Point{samples.back().x_m + std::sin(a), samples.back().y_m + std::cos(a)};
    samples.push_back({static_cast<double>(k), p.x_m, p.y_m, heading_deg, 1.0});
    heading_deg += k % 2 == 0 ? 5.0 : 20.0;
  }
  TurnSequence turn(meta, samples);
  turn.fill_derived_metadata();
  const TurnMeasures m = measure_turn(turn);
  EXPECT_FALSE(m.steady_turning_radius_m);
  EXPECT_FALSE(m.steady_yaw_rate_dps);
}

TEST(TurnMeasures, SixtyDegreeTurnHasNoNinetyOrHalfTurnMeasures) {
  const TurnMeasures m = measure_turn(make_arc_turn(arc(60.0, 2.0, 3.0)));
  EXPECT_FALSE(m.advance_90_m);
  EXPECT_FALSE(m.transfer_90_m);
  EXPECT_FALSE(m.time_to_90_s);
  EXPECT_FALSE(m.tactical_diameter_m);
  EXPECT_FALSE(m.time_to_180_s);
  EXPECT_NEAR(m.at_end.advance_m, 2.0 + 3.0 * std::sin(deg_to_rad(60.0)), 1e-9);
  ASSERT_TRUE(m.overshoot_deg);  // goal reached, no overshoot: zero, not absent
  EXPECT_NEAR(*m.overshoot_deg, 0.0, 1e-9);
  EXPECT_TRUE(m.distance_to_first_10deg_m);
}

TEST(TurnMeasures, OvershootBeyondTheGoal) {
  auto past = make_arc_turn(arc(70.0, 2.0, 3.0));
  past.meta().goal_dheading_deg = 60.0;
  const TurnMeasures m = measure_turn(past);
  ASSERT_TRUE(m.overshoot_deg);
  EXPECT_NEAR(*m.overshoot_deg, 10.0, 1e-6);

  // Swings 8 degrees past a 60-degree goal and settles back on it.
  TurnMeta meta;
  meta.goal_dheading_deg = -60.0;
  TurnSequence swing(meta, {{0, 0, 0, 0, 1},
                            {1, 0, 1, 340, 1},
                            {2, -0.5, 1.8, 310, 1},
                            {3, -1.3, 2.4, 292, 1},
                            {4, -2.2, 2.8, 296, 1},
                            {5, -3.1, 3.2, 300, 1}});
  swing.fill_derived_metadata();
  const TurnMeasures s = measure_turn(swing);
  ASSERT_TRUE(s.overshoot_deg);
  EXPECT_NEAR(*s.overshoot_deg, 8.0, 1e-9);
  ASSERT_TRUE(s.max_dheading_deg);
  EXPECT_NEAR(*s.max_dheading_deg, 68.0, 1e-9);

  auto short_of_goal = make_arc_turn(arc(50.0, 2.0, 3.0));
  short_of_goal.meta().goal_dheading_deg = 60.0;
  EXPECT_FALSE(measure_turn(short_of_goal).overshoot_deg);
}

TEST(TurnMeasures, DistanceToFirstTenDegrees) {
  for (double lead_m : {0.0, 1.0, 4.0}) {
    const double radius_m = 5.0;
    const TurnMeasures m = measure_turn(make_arc_turn(arc(-90.0, lead_m, radius_m)));
    ASSERT_TRUE(m.distance_to_first_10deg_m);
    EXPECT_NEAR(*m.distance_to_first_10deg_m, lead_m + radius_m * deg_to_rad(10.0), 1e-3);
  }
}

TEST(TurnMeasures, SpeedLoss) {
  auto turn = make_arc_turn(arc(90.0, 2.0, 3.0, 2.0));
  std::vector<TurnSample> samples = turn.samples();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    // Slows to 1.4 m/s half-way through, recovers to 1.8 m/s.
    const double f = static_cast<double>(i) / static_cast<double>(samples.size() - 1);
    samples[i].speed_mps = f < 0.5 ? 2.0 - 1.2 * f : 1.4 + 0.8 * (f - 0.5);
  }
  const TurnSequence slowed(turn.meta(), samples);
  const TurnMeasures m = measure_turn(slowed);
  ASSERT_TRUE(m.speed_loss_mps && m.speed_loss_fraction);
  EXPECT_NEAR(*m.speed_loss_mps, 0.6, 0.02);
  EXPECT_NEAR(*m.speed_loss_fraction, 0.3, 0.01);
  EXPECT_NEAR(*measure_turn(turn).speed_loss_mps, 0.0, 1e-12);

  for (auto& s : samples)
    s.speed_mps = 0.0;  // speed not recorded
  EXPECT_FALSE(measure_turn(TurnSequence(turn.meta(), samples)).speed_loss_mps);
}

TEST(TurnMeasures, LengthsInVehicleLengths) {
  EXPECT_DOUBLE_EQ(*in_vehicle_lengths(6.0, 1.5), 4.0);
  EXPECT_FALSE(in_vehicle_lengths(std::nullopt, 1.5));
  EXPECT_FALSE(in_vehicle_lengths(6.0, std::nullopt));
  EXPECT_FALSE(in_vehicle_lengths(6.0, 0.0));
  const TurnMeasures m = measure_turn(make_arc_turn(arc(120.0, 2.0, 3.0)), 1.25);
  ASSERT_TRUE(m.vehicle_length_m);
  EXPECT_DOUBLE_EQ(*m.vehicle_length_m, 1.25);
  EXPECT_NEAR(*in_vehicle_lengths(m.advance_90_m, m.vehicle_length_m), 5.0 / 1.25, 3e-3);
  EXPECT_FALSE(in_vehicle_lengths(m.tactical_diameter_m, m.vehicle_length_m));
}

TEST(TurnMeasures, LeftTurnMeasuresLikeItsMirroredRightTurn) {
  ArcTurnSpec right = arc(110.0, 1.7, 3.3, 1.1, 0.2);
  right.start = {10.0, 20.0, 300.0};
  ArcTurnSpec left = right;
  left.dheading_deg = -110.0;
  left.start = {-5.0, 7.0, 45.0};
  const TurnMeasures r = measure_turn(make_arc_turn(right), 1.0);
  const TurnMeasures l = measure_turn(make_arc_turn(left), 1.0);
  EXPECT_NEAR(r.at_end.advance_m, l.at_end.advance_m, 1e-9);
  EXPECT_NEAR(r.at_end.transfer_m, l.at_end.transfer_m, 1e-9);
  EXPECT_GT(l.at_end.transfer_m, 0.0);  // towards the turn side, also for a left turn
  expect_same(r.advance_90_m, l.advance_90_m, "advance_90");
  expect_same(r.transfer_90_m, l.transfer_90_m, "transfer_90");
  expect_same(r.tactical_diameter_m, l.tactical_diameter_m, "tactical");
  expect_same(r.steady_turning_radius_m, l.steady_turning_radius_m, "steady radius");
  expect_same(r.time_to_90_s, l.time_to_90_s, "time_to_90");
  expect_same(r.speed_loss_mps, l.speed_loss_mps, "speed loss");
  expect_same(r.distance_to_first_10deg_m, l.distance_to_first_10deg_m, "first 10");
  expect_same(r.overshoot_deg, l.overshoot_deg, "overshoot");
  ASSERT_TRUE(r.advance_90_m);
  EXPECT_NEAR(*r.advance_90_m, 1.7 + 3.3, 3e-3);
}

TEST(TurnMeasures, RejectsTurnsWithoutEnoughSamples) {
  TurnMeta meta;
  meta.goal_dheading_deg = 90.0;
  EXPECT_THROW(measure_turn(TurnSequence(meta, {})), std::invalid_argument);
  EXPECT_THROW(measure_turn(TurnSequence(meta, {{0, 0, 0, 0, 1}})), std::invalid_argument);
  EXPECT_THROW(advance_transfer(Polyline{}), std::invalid_argument);
  EXPECT_THROW(advance_transfer(TurnSequence(meta, {})), std::invalid_argument);
}
