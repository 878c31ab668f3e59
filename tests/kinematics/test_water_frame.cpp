// Turns in a current (kinematics/water_frame.hpp): an arc through the water carried by a known
// uniform current comes back exactly when the drift is removed, and a prediction through the water
// plus the drift lands where the carried arc went.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/water_frame.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

// The arc carried by the current: every sample moved by c·(t − t0), as a GNSS would see it.
TurnSequence carried(const TurnSequence& water, WaterCurrent c) {
  std::vector<TurnSample> s = water.samples();
  for (auto& p : s) {
    const double dt = p.t_s - water.samples().front().t_s;
    p.x_m += c.east_mps * dt;
    p.y_m += c.north_mps * dt;
  }
  return TurnSequence(water.meta(), std::move(s));
}

TEST(WaterFrame, RemovingTheDriftRecoversTheArcThroughTheWater) {
  for (double heading : {0.0, 73.0, 200.0}) {
    for (double dpsi : {90.0, -135.0}) {
      ArcTurnSpec spec;
      spec.dheading_deg = dpsi;
      spec.start = {12.0, -5.0, heading};
      const TurnSequence water = make_arc_turn(spec);
      const WaterCurrent c{0.15, -0.25};
      const TurnSequence ground = carried(water, c);
      ASSERT_GT(distance_m(ground.points().back(), water.points().back()), 1.0);
      const TurnSequence back = in_water_frame(ground, c);
      ASSERT_EQ(back.samples().size(), water.samples().size());
      for (std::size_t i = 0; i < back.samples().size(); ++i) {
        EXPECT_NEAR(back.samples()[i].x_m, water.samples()[i].x_m, 1e-9);
        EXPECT_NEAR(back.samples()[i].y_m, water.samples()[i].y_m, 1e-9);
        EXPECT_EQ(back.samples()[i].heading_deg, water.samples()[i].heading_deg);
      }
      ASSERT_TRUE(back.meta().removed_current);
      EXPECT_EQ(*back.meta().removed_current, c);
      // Normalising keeps the record of the frame.
      EXPECT_EQ(back.normalized().meta().removed_current, c);
    }
  }
}

TEST(WaterFrame, SpeedThroughTheWaterIsTheGroundSpeedLessTheCurrentAlongTheHeading) {
  ArcTurnSpec spec;
  spec.dheading_deg = 90.0;  // from north to east
  spec.speed_mps = 1.0;
  const TurnSequence t = make_arc_turn(spec);
  // A current toward north: against the start's ground speed it adds 0.2 along the heading.
  const TurnSequence w = in_water_frame(t, {0.0, 0.2});
  EXPECT_NEAR(w.samples().front().speed_mps, t.samples().front().speed_mps - 0.2, 1e-12);
  EXPECT_NEAR(w.samples().back().speed_mps, t.samples().back().speed_mps, 1e-12);  // heading east
  EXPECT_NEAR(w.meta().initial_speed_mps, w.samples().front().speed_mps, 1e-12);
}

TEST(WaterFrame, RefusesWhatItCannotMove) {
  const TurnSequence t = make_arc_turn(ArcTurnSpec{});
  EXPECT_THROW(in_water_frame(t.normalized(), {0.1, 0.0}), std::invalid_argument);
  EXPECT_THROW(in_water_frame(in_water_frame(t, {0.1, 0.0}), {0.1, 0.0}), std::invalid_argument);
  EXPECT_THROW(in_water_frame(t, {std::nan(""), 0.0}), std::invalid_argument);
}

TEST(WaterFrame, CurrentInTheNormalisedFrameTurnsWithTheHeadingAndMirrorsForALeftTurn) {
  // Heading east: a current toward east is straight ahead, one toward south is to starboard.
  const Point ahead = current_in_normalized_frame({0.3, 0.0}, 90.0, TurnSide::right);
  EXPECT_NEAR(ahead.x_m, 0.0, 1e-12);
  EXPECT_NEAR(ahead.y_m, 0.3, 1e-12);
  const Point starboard = current_in_normalized_frame({0.0, -0.3}, 90.0, TurnSide::right);
  EXPECT_NEAR(starboard.x_m, 0.3, 1e-12);
  EXPECT_NEAR(starboard.y_m, 0.0, 1e-12);
  const Point mirrored = current_in_normalized_frame({0.0, -0.3}, 90.0, TurnSide::left);
  EXPECT_NEAR(mirrored.x_m, -0.3, 1e-12);
  // Rotation leaves the speed alone.
  const Point any = current_in_normalized_frame({0.1, 0.2}, 237.0, TurnSide::left);
  EXPECT_NEAR(std::hypot(any.x_m, any.y_m), std::hypot(0.1, 0.2), 1e-12);
}

// The normalised ground turn is the normalised water turn plus the current in the normalised
// frame times the time: what a compensated prediction adds.
TEST(WaterFrame, NormalisedGroundTurnIsTheWaterTurnPlusTheRotatedDrift) {
  ArcTurnSpec spec;
  spec.dheading_deg = -120.0;
  spec.start = {3.0, 4.0, 310.0};
  const WaterCurrent c{-0.2, 0.1};
  const TurnSequence water = make_arc_turn(spec);
  const TurnSequence ground = carried(water, c);
  const Point cn = current_in_normalized_frame(c, ground.meta().initial_heading_deg, ground.side());
  const auto gn = ground.normalized().samples();
  const auto wn = water.normalized().samples();
  for (std::size_t i = 0; i < gn.size(); ++i) {
    const double dt = gn[i].t_s - gn.front().t_s;
    EXPECT_NEAR(gn[i].x_m, wn[i].x_m + cn.x_m * dt, 1e-9);
    EXPECT_NEAR(gn[i].y_m, wn[i].y_m + cn.y_m * dt, 1e-9);
  }
}

TEST(WaterFrame, DriftedPathAndClockStations) {
  const TimedPath p{{0.0, 0.0, 0.0}, {2.0, 0.0, 2.0}, {4.0, 0.0, 4.0}};
  const TimedPath d = drifted(p, {0.5, -0.25});
  EXPECT_EQ(d[0], (TimedPoint{0.0, 0.0, 0.0}));
  EXPECT_EQ(d[2], (TimedPoint{4.0, 2.0, 3.0}));
  const StationedPath s = stationed_by_clock(d, 1.0);
  EXPECT_EQ(s.s_m, (std::vector<double>{0.0, 2.0, 4.0}));
  EXPECT_EQ(s.points[1], (Point{1.0, 1.5}));
  EXPECT_THROW(stationed_by_clock({}, 1.0), std::invalid_argument);
  EXPECT_THROW(stationed_by_clock(p, 0.0), std::invalid_argument);
}

TEST(WaterFrame, TurnJsonKeepsTheRemovedCurrentAndOldDocumentsLoadWithout) {
  const TurnSequence t = in_water_frame(make_arc_turn(ArcTurnSpec{}), {0.125, -0.5});
  const TurnSequence back = parse_turn_json(to_json_string(t));
  EXPECT_EQ(back.meta().removed_current, t.meta().removed_current);
  const TurnSequence plain = make_arc_turn(ArcTurnSpec{});
  const std::string text = to_json_string(plain);
  EXPECT_EQ(text.find("removed_current"), std::string::npos);
  EXPECT_FALSE(parse_turn_json(text).meta().removed_current);
  auto half = to_json(t);
  half.erase("removed_current_north_mps");
  try {
    parse_turn_json(half.dump());
    FAIL() << "half a current loaded";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "/removed_current_north_mps");
  }
}

TEST(WaterFrame, CurrentFromTurnResidualsGrowingLinearly) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  const WaterCurrent truth{0.12, -0.2};
  std::vector<TurnResidual> turns;
  for (int k = 0; k < 12; ++k) {
    TurnResidual r;
    for (int i = 0; i <= 100; ++i) {
      const double t = 0.1 * i;
      r.t_s.push_back(t);
      r.residual_m.push_back({truth.east_mps * t + noise(rng), truth.north_mps * t + noise(rng)});
    }
    turns.push_back(std::move(r));
  }
  const auto got = estimate_current_from_turns(turns);
  ASSERT_TRUE(got.estimate) << got.why_not;
  EXPECT_NEAR(got.estimate->east_mps, truth.east_mps, 0.01);
  EXPECT_NEAR(got.estimate->north_mps, truth.north_mps, 0.01);
  EXPECT_EQ(got.estimate->legs, 12u);
  EXPECT_GT(got.estimate->speed_sd_mps(), 0.0);
  EXPECT_FALSE(estimate_current_from_turns({turns.front()}).estimate);
}

// A candidate through the water drifts with the current: heading north at 1 m/s in 0.5 m/s
// toward east, the vehicle is at (5, 10) after 10 s, where a stationary contact sits. A vehicle
// holding 1 m/s over ground instead makes good sqrt(0.75) m/s north: it passes that contact's
// latitude later and further east.
TEST(WaterFrame, ManeuverCandidatesDriftWithTheCurrent) {
  const Polyline straight{{0.0, 0.0}, {0.0, 40.0}};
  const PredictedManeuver m = timed_maneuver(0.0, 1.0, straight, std::nullopt);
  ManeuverProblem p;
  p.contacts = {Contact{5.0, 10.0, 0.0, 0.0}};
  p.horizon_s = 30.0;
  const CandidateEvaluation still = evaluate_candidate(p, m);
  EXPECT_NEAR(still.min_cpa_m, 5.0, 1e-9);
  p.current = WaterCurrent{0.5, 0.0};
  p.speed_over_ground = false;
  const CandidateEvaluation drifting = evaluate_candidate(p, m);
  EXPECT_NEAR(drifting.min_cpa_m, 0.0, 1e-9);
  p.speed_over_ground = true;
  const CandidateEvaluation held = evaluate_candidate(p, m);
  const TimedPoint& end = held.path.back();
  EXPECT_NEAR(end.t_s, 30.0, 1e-9);
  EXPECT_NEAR(end.x_m, 15.0, 1e-9);
  EXPECT_NEAR(end.y_m, 30.0 * std::sqrt(0.75), 1e-9);
  // At the contact's latitude (t = 10/sqrt(0.75) s) it is 5.77 m east: the CPA is across.
  EXPECT_NEAR(held.min_cpa_m, std::hypot(10.0 / std::sqrt(0.75) * 0.5 - 5.0, 0.0) * std::sqrt(0.75),
              1e-6);
}

TEST(WaterFrame, TableFrameFollowsItsTurnsAndTravelsInTheFile) {
  std::vector<TurnSequence> turns;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    ArcTurnSpec spec;
    spec.seed = seed;
    spec.position_noise_m = 0.02;
    turns.push_back(make_arc_turn(spec));
  }
  EXPECT_EQ(Ckt::build(turns).frame, TableFrame::ground);
  std::vector<TurnSequence> water;
  for (const auto& t : turns)
    water.push_back(in_water_frame(t, {0.1, 0.0}));
  CktBuildReport report;
  const Ckt w = Ckt::build(water, {}, std::nullopt, &report);
  EXPECT_EQ(w.frame, TableFrame::water);
  EXPECT_EQ(report.turns_water_frame, 3u);
  water.pop_back();
  water.push_back(turns.back());
  EXPECT_EQ(Ckt::build(water).frame, TableFrame::mixed);
  EXPECT_EQ(parse_ckt_json(ckt_to_json_string(w)).frame, TableFrame::water);
  // A schema 3 document has no frame: it loads as a table over ground, and refuses one.
  auto doc = ckt_to_json(w);
  doc["schema_version"] = 3;
  doc.erase("frame");
  EXPECT_EQ(ckt_from_json(doc).frame, TableFrame::ground);
  doc["frame"] = "water";
  EXPECT_THROW(ckt_from_json(doc), ParseError);
}

}  // namespace
