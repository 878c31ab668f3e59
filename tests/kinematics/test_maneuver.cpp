// Maneuver evaluation by closest point of approach: CPA against analytic cases (parallel tracks,
// head-on, a circle arc against a straight line), the corridor's nearer edge, invariance under
// moving the whole encounter, the choice rule on hand-made candidates, and the ongoing
// evaluation on a recorded turn replayed sample by sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/maneuver.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using namespace avk::kinematics;

// Straight at speed u along heading h from p for duration T, one point every dt.
TimedPath straight(Point p, double heading_deg, double u, double T, double dt = 1.0) {
  TimedPath out;
  for (double t = 0.0; t <= T + 1e-9; t += dt) {
    const Point d = rotate_by_heading({0.0, u * t}, heading_deg);
    out.push_back({t, p.x_m + d.x_m, p.y_m + d.y_m});
  }
  return out;
}

TEST(Cpa, ParallelTracksKeepTheirSpacing) {
  const TimedPath own = straight({0.0, 0.0}, 0.0, 1.0, 60.0);
  const Approach a = closest_approach(own, {10.0, 0.0, 0.0, 1.0});
  EXPECT_NEAR(a.distance_m, 10.0, 1e-9);
}

TEST(Cpa, OffsetHeadOnMeetsAtTheMidpointInTime) {
  // Contact 50 m ahead, 10 m to starboard, coming south at 1 m/s: abeam after 25 s at 10 m.
  const TimedPath own = straight({0.0, 0.0}, 0.0, 1.0, 60.0, 7.0);
  const Approach a = closest_approach(own, {10.0, 50.0, 180.0, 1.0});
  EXPECT_NEAR(a.distance_m, 10.0, 1e-9);
  EXPECT_NEAR(a.time_s, 25.0, 1e-9);
}

TEST(Cpa, HeadOnOnTheSameLineCollides) {
  const TimedPath own = straight({0.0, 0.0}, 0.0, 1.5, 100.0, 3.0);
  const Approach a = closest_approach(own, {0.0, 100.0, 180.0, 0.5});
  EXPECT_NEAR(a.distance_m, 0.0, 1e-9);
  EXPECT_NEAR(a.time_s, 50.0, 1e-9);
}

TEST(Cpa, OvertakingASlowerContactAhead) {
  // 20 m ahead and 3 m to port, 0.5 m/s slower: abeam after 40 s.
  const TimedPath own = straight({0.0, 0.0}, 90.0, 1.0, 120.0, 2.5);
  const Approach a = closest_approach(own, {20.0, 3.0, 90.0, 0.5});
  EXPECT_NEAR(a.distance_m, 3.0, 1e-9);
  EXPECT_NEAR(a.time_s, 40.0, 1e-9);
}

TEST(Cpa, ACircleArcAgainstAStraightLineMatchesTheAnalyticMinimum) {
  // Own: a right circle of radius R at speed u from the origin heading north, centre (R, 0).
  const double R = 6.0, u = 1.0, w = u / R;
  const auto own_at = [&](double t) {
    return Point{R * (1.0 - std::cos(w * t)), R * std::sin(w * t)};
  };
  TimedPath own;
  for (double t = 0.0; t <= 40.0 + 1e-9; t += 0.05)
    own.push_back({t, own_at(t).x_m, own_at(t).y_m});
  for (const Contact c : {Contact{30.0, 5.0, 270.0, 1.2}, Contact{-10.0, 20.0, 120.0, 0.8},
                          Contact{R, 0.0, 0.0, 0.0}}) {
    // The exact minimum of the distance between the analytic circle and the contact's line.
    double best = 1e300, best_t = 0.0;
    for (double t = 0.0; t <= 40.0; t += 1e-3) {
      const Point p = own_at(t), q = contact_position(c, t);
      const double d = std::hypot(p.x_m - q.x_m, p.y_m - q.y_m);
      if (d < best) best = d, best_t = t;
    }
    const Approach a = closest_approach(own, c);
    // A chord of 0.05 rad/6 deviates from the circle by R (1 - cos(dθ/2)) < 1e-4 m.
    EXPECT_NEAR(a.distance_m, best, 2e-4) << c.x_m;
    if (c.speed_mps > 0.0) {
      EXPECT_NEAR(a.time_s, best_t, 0.05) << c.x_m;
    }
  }
  // The stationary contact at the centre stays at the radius.
  EXPECT_NEAR(closest_approach(own, {R, 0.0, 0.0, 0.0}).distance_m, R, 1e-3);
}

TEST(Cpa, AStandingPathIsAPoint) {
  const TimedPath own{{0.0, 3.0, 4.0}};
  EXPECT_NEAR(closest_approach(own, {0.0, 0.0, 0.0, 0.0}).distance_m, 5.0, 1e-12);
  EXPECT_THROW(closest_approach({}, {}), std::invalid_argument);
}

TEST(Cpa, TheCorridorsNearerEdgeIsTheDistanceLessTheHalfWidth) {
  const TimedPath own = straight({0.0, 0.0}, 0.0, 1.0, 60.0);
  const std::vector<double> w(own.size(), 1.5);
  const Approach parallel = closest_approach_of_corridor(own, w, {10.0, 0.0, 0.0, 1.0});
  EXPECT_NEAR(parallel.distance_m, 8.5, 1e-9);
  // A contact that crosses the corridor touches it.
  EXPECT_NEAR(closest_approach_of_corridor(own, w, {10.0, 20.0, 270.0, 0.5}).distance_m, 0.0, 1e-9);
  // A corridor that widens along the path: its edge is nearest where it is widest.
  std::vector<double> widening;
  for (const TimedPoint& p : own)
    widening.push_back(0.05 * p.t_s);
  const Approach e = closest_approach_of_corridor(own, widening, {10.0, 0.0, 0.0, 1.0});
  EXPECT_NEAR(e.distance_m, 10.0 - 3.0, 1e-9);
  EXPECT_NEAR(e.time_s, 60.0, 1e-9);
  EXPECT_THROW(closest_approach_of_corridor(own, {1.0}, {}), std::invalid_argument);
}

TEST(Cpa, MovingTheWholeEncounterChangesNothing) {
  // Rotation, translation and reflection of own path and contact together.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50.0, 50.0), h(0.0, 360.0), v(0.0, 2.0);
  const Polyline arc = avk::testing::circular_arc(5.0, 120.0, 0.2);
  const PredictedManeuver m =
      extended_to_horizon(timed_maneuver(120.0, 1.0, arc, std::nullopt), 90.0);
  for (int k = 0; k < 50; ++k) {
    const Contact c{u(rng), u(rng), h(rng), v(rng)};
    const double base = closest_approach(m.path, c).distance_m;
    const Pose pose{u(rng), u(rng), h(rng)};
    const Point cp = rotate_by_heading({c.x_m, c.y_m}, pose.heading_deg);
    const Contact moved{pose.x_m + cp.x_m, pose.y_m + cp.y_m,
                        wrap360_deg(c.course_deg + pose.heading_deg), c.speed_mps};
    EXPECT_NEAR(closest_approach(placed(m.path, pose), moved).distance_m, base, 1e-9);
    // The mirror image: a left turn against the mirrored contact.
    TimedPath mirrored = m.path;
    for (TimedPoint& p : mirrored)
      p.x_m = -p.x_m;
    const Contact mc{-c.x_m, c.y_m, wrap360_deg(-c.course_deg), c.speed_mps};
    EXPECT_NEAR(closest_approach(mirrored, mc).distance_m, base, 1e-9);
  }
}

TEST(TimedManeuver, AtConstantSpeedTimeIsLengthOverSpeed) {
  const Polyline arc = avk::testing::circular_arc(4.0, 90.0, 0.1);
  const PredictedManeuver m = timed_maneuver(90.0, 2.0, arc, std::nullopt);
  const auto s = cumulative_arc_length_m(arc);
  ASSERT_EQ(m.path.size(), arc.size());
  for (std::size_t i = 0; i < arc.size(); ++i)
    EXPECT_NEAR(m.path[i].t_s, s[i] / 2.0, 1e-12);
  EXPECT_FALSE(m.timed_by_turns);
  // Past its end it holds the new heading (east) at its speed up to the horizon.
  const PredictedManeuver e = extended_to_horizon(m, 30.0);
  EXPECT_NEAR(e.path.back().t_s, 30.0, 1e-12);
  const double run = (30.0 - m.path.back().t_s) * 2.0;
  EXPECT_NEAR(e.path.back().x_m, arc.back().x_m + run, 1e-9);
  EXPECT_NEAR(e.path.back().y_m, arc.back().y_m, 1e-9);
  // A horizon inside the path cuts it there, on the path.
  const PredictedManeuver cut = extended_to_horizon(m, 1.0);
  EXPECT_NEAR(cut.path.back().t_s, 1.0, 1e-12);
  EXPECT_NEAR(std::hypot(cut.path.back().x_m - 4.0, cut.path.back().y_m), 4.0, 1e-3);
}

TEST(TimedManeuver, ATimingFromSlowerTurnsMakesThePathLater) {
  const Polyline line{{0.0, 0.0}, {0.0, 10.0}};
  TurnTiming slow = constant_speed_timing(10.0, 0.5);
  const PredictedManeuver m = timed_maneuver(0.0, 1.0, line, slow);
  EXPECT_TRUE(m.timed_by_turns);
  EXPECT_NEAR(m.path.back().t_s, 20.0, 1e-12);
  EXPECT_THROW(timed_maneuver(0.0, 1.0, line, std::nullopt, {1.0}), std::invalid_argument);
}

CandidateEvaluation candidate(double d, bool clears) {
  CandidateEvaluation c;
  c.dheading_deg = d;
  c.clears = clears;
  return c;
}

TEST(Choice, TheSmallestClearingHeadingChangeTiesToStarboard) {
  EXPECT_EQ(choose_maneuver({candidate(-10, true), candidate(0, false), candidate(10, true),
                             candidate(20, true)}),
            2u);
  EXPECT_EQ(choose_maneuver({candidate(10, true), candidate(-10, true)}), 0u);
  EXPECT_EQ(choose_maneuver({candidate(-5, true), candidate(10, true)}), 0u);
  EXPECT_EQ(choose_maneuver({candidate(0, true), candidate(5, true)}), 0u);
  EXPECT_EQ(choose_maneuver({candidate(-180, true), candidate(180, true)}), 1u);
  EXPECT_FALSE(choose_maneuver({candidate(-10, false), candidate(10, false)}));
  EXPECT_FALSE(choose_maneuver({}));
}

TEST(Choice, CandidatesAreSymmetricAndIncludeKeepingCourse) {
  const auto c = candidate_dheadings_deg();
  ASSERT_EQ(c.size(), 73u);
  EXPECT_EQ(c.front(), -180.0);
  EXPECT_EQ(c.back(), 180.0);
  EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
  EXPECT_NE(std::find(c.begin(), c.end(), 0.0), c.end());
  const auto seven = candidate_dheadings_deg(7.0);
  EXPECT_NE(std::find(seven.begin(), seven.end(), 0.0), seven.end());
  EXPECT_NE(std::find(seven.begin(), seven.end(), -7.0), seven.end());
  EXPECT_EQ(seven.back(), 180.0);
  EXPECT_THROW(candidate_dheadings_deg(0.0), std::invalid_argument);
}

TEST(Evaluate, ACrossingFromStarboardIsClearedByTurningAway) {
  // Own north at 1 m/s; a contact crossing from starboard aimed at where own will be in 30 s.
  ManeuverProblem p;
  p.own = {0.0, 0.0, 0.0};
  p.contacts = {{30.0, 30.0, 270.0, 1.0}};
  p.standoff_m = 8.0;
  p.horizon_s = 90.0;
  std::vector<CandidateEvaluation> all;
  for (double d : candidate_dheadings_deg(5.0)) {
    const Point end = rotate_by_heading({0.0, 90.0}, d);
    all.push_back(evaluate_candidate(p, timed_maneuver(d, 1.0, {{0.0, 0.0}, end}, std::nullopt)));
  }
  const auto keep =
      std::find_if(all.begin(), all.end(), [](auto& c) { return c.dheading_deg == 0; });
  EXPECT_NEAR(keep->min_cpa_m, 0.0, 1e-9);
  EXPECT_FALSE(keep->clears);
  const auto chosen = choose_maneuver(all);
  ASSERT_TRUE(chosen);
  EXPECT_GE(all[*chosen].min_cpa_m, 8.0);
  // Every candidate with a smaller change does not clear.
  for (const auto& c : all)
    if (std::abs(c.dheading_deg) < std::abs(all[*chosen].dheading_deg)) {
      EXPECT_FALSE(c.clears) << c.dheading_deg;
    }
  // The path runs to the horizon in the world frame.
  EXPECT_NEAR(all[*chosen].path.back().t_s, 90.0, 1e-9);
}

TEST(Evaluate, TheCorridorMakesACandidateThatJustClearsFail) {
  ManeuverProblem p;
  p.contacts = {{10.5, 0.0, 0.0, 1.0}};
  p.standoff_m = 10.0;
  p.horizon_s = 30.0;
  const Polyline line{{0.0, 0.0}, {0.0, 30.0}};
  const PredictedManeuver bare = timed_maneuver(0.0, 1.0, line, std::nullopt);
  const PredictedManeuver wide = timed_maneuver(0.0, 1.0, line, std::nullopt, {1.0, 1.0});
  EXPECT_TRUE(evaluate_candidate(p, bare).clears);
  const CandidateEvaluation e = evaluate_candidate(p, wide);
  EXPECT_FALSE(e.clears);
  ASSERT_TRUE(e.min_edge_cpa_m);
  EXPECT_NEAR(*e.min_edge_cpa_m, 9.5, 1e-9);
  p.use_corridor = false;
  EXPECT_TRUE(evaluate_candidate(p, wide).clears);
}

// A table of arc turns with GNSS-like noise, and a held-out turn of the same kind replayed sample
// by sample as a turn in progress.
TEST(Ongoing, ARecordedTurnReplayedSampleBySampleStaysOnItsPrediction) {
  std::vector<TurnSequence> turns;
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = 1.0;
  spec.dheading_deg = 90.0;
  spec.lead_in_m = 1.0;
  spec.radius_m = 4.0;
  spec.dt_s = 0.1;
  spec.tail_m = 3.0;
  spec.position_noise_m = 0.05;
  for (unsigned s = 1; s <= 6; ++s) {
    spec.seed = s;
    turns.push_back(avk::testing::make_arc_turn(spec));
  }
  const Ckt table = Ckt::build(turns);
  const TurnPrediction t = table.query(1.0, 90.0);
  ASSERT_TRUE(t.timing);
  ASSERT_TRUE(t.corridor);
  const auto band = corridor_band(t.trajectory, *t.corridor, 0.9);
  const PredictedManeuver m = extended_to_horizon(
      timed_maneuver(90.0, 1.0, t.trajectory, t.timing, band.half_width_m), 60.0);
  EXPECT_TRUE(m.timed_by_turns);
  // The held-out turn, flown from a pose in the world.
  spec.seed = 99;
  spec.start = {12.0, -7.0, 250.0};
  const TurnSequence held_out = avk::testing::make_arc_turn(spec);
  const TimedPath prediction = placed(m.path, spec.start);
  std::size_t inside = 0, total = 0;
  double worst = 0.0;
  for (const TurnSample& s : held_out.samples()) {
    const double elapsed = s.t_s - held_out.samples().front().t_s;
    const OngoingEvaluation e =
        evaluate_ongoing(prediction, m.half_width_m, elapsed, Point{s.x_m, s.y_m});
    ASSERT_TRUE(e.deviation_m && e.cross_track_m && e.inside_corridor && e.half_width_m);
    worst = std::max(worst, *e.deviation_m);
    EXPECT_LE(*e.cross_track_m, *e.deviation_m + 1e-9);
    ASSERT_FALSE(e.remaining.empty());
    EXPECT_EQ(e.remaining.front().x_m, e.expected.x_m);
    for (std::size_t k = 1; k < e.remaining.size(); ++k)
      EXPECT_GT(e.remaining[k].t_s, elapsed);
    inside += *e.inside_corridor ? 1 : 0;
    ++total;
  }
  // Noise of 5 cm on a 4 m turn: the vehicle is where the prediction says, in time as in space.
  EXPECT_LT(worst, 0.35);
  EXPECT_GE(static_cast<double>(inside) / static_cast<double>(total), 0.75);
}

TEST(Ongoing, AVehicleRunningLateIsOnThePathButBehindItsTime) {
  avk::testing::ArcTurnSpec spec;
  spec.dheading_deg = 90.0;
  spec.radius_m = 4.0;
  spec.tail_m = 5.0;
  const TurnSequence planned = avk::testing::make_arc_turn(spec);
  Polyline line;
  for (const TurnSample& s : planned.samples())
    line.push_back({s.x_m, s.y_m});
  const PredictedManeuver m = timed_maneuver(90.0, 1.0, line, std::nullopt);
  // At half speed, after 6 s the vehicle is where the prediction was after 3 s.
  const Point late = avk::testing::arc_turn_point(spec, 3.0, nullptr);
  const OngoingEvaluation e = evaluate_ongoing(m.path, {}, 6.0, late);
  EXPECT_NEAR(*e.cross_track_m, 0.0, 1e-6);
  const Point expected = avk::testing::arc_turn_point(spec, 6.0, nullptr);
  EXPECT_NEAR(*e.deviation_m, distance_m(late, expected),
              2e-3);                // chords of 0.25 m are shorter than the arc
  EXPECT_FALSE(e.inside_corridor);  // no corridor, no verdict
  // Past the end the vehicle should be at the last point.
  const OngoingEvaluation after = evaluate_ongoing(m.path, {}, 1e3, std::nullopt);
  EXPECT_EQ(after.expected.x_m, m.path.back().x_m);
  EXPECT_EQ(after.remaining.size(), 1u);
  EXPECT_THROW(evaluate_ongoing(m.path, {}, -1.0, std::nullopt), std::invalid_argument);
}

TEST(Ongoing, AtTheCommandTheBandJudgesNotTheZeroWidthCorridor) {
  // A straight 10 m path north in 10 s; the corridor is 0 m at the command and 1 m at the end;
  // the band is the navigation's noise, 0.3 m each axis, growing to 2 m across at the end.
  const TimedPath path{{0.0, 0.0, 0.0}, {10.0, 0.0, 10.0}};
  const std::vector<double> corridor{0.0, 1.0};
  const OngoingBand band{{{0.09, 0.0, 0.09}, {4.0, 0.0, 0.09}}, 0.9};
  // 0.2 m east at the command: the corridor alone says outside, the band inside.
  const OngoingEvaluation start = evaluate_ongoing(path, corridor, 0.0, Point{0.2, 0.0});
  ASSERT_TRUE(start.inside_corridor);
  EXPECT_FALSE(*start.inside_corridor);
  const OngoingEvaluation judged = evaluate_ongoing(path, corridor, 0.0, Point{0.2, 0.0}, band);
  ASSERT_TRUE(judged.inside_band && judged.inside_corridor && judged.band_ellipse);
  EXPECT_TRUE(*judged.inside_band);
  EXPECT_TRUE(*judged.inside_corridor);
  EXPECT_DOUBLE_EQ(*judged.half_width_m, 0.0);  // still reported as it is
  // 2 m east at the command is outside the 0.3 m noise.
  EXPECT_FALSE(*evaluate_ongoing(path, corridor, 0.0, Point{2.0, 0.0}, band).inside_corridor);
  // Halfway in time the covariance is halfway between the points': xx = (0.09 + 4) / 2.
  const OngoingEvaluation half = evaluate_ongoing(path, corridor, 5.0, Point{2.0, 5.0}, band);
  ASSERT_TRUE(half.band_m2);
  EXPECT_NEAR((*half.band_m2)[0], 2.045, 1e-12);
  EXPECT_NEAR((*half.band_m2)[2], 0.09, 1e-12);
  // 2 m across with sd 1.43 m is within the 90 % band (k = 2.146), and the major axis is east.
  EXPECT_TRUE(*half.inside_corridor);
  EXPECT_NEAR(half.band_ellipse->major_axis_deg, 90.0, 1e-9);
  EXPECT_NEAR(half.band_ellipse->major_m, band_radius_factor(0.9) * std::sqrt(2.045), 1e-9);
  // Past the end the band is the last point's.
  EXPECT_NEAR((*evaluate_ongoing(path, corridor, 50.0, std::nullopt, band).band_m2)[0], 4.0, 0.0);
  // Without a measured position there is no verdict, with or without a band.
  EXPECT_FALSE(evaluate_ongoing(path, corridor, 5.0, std::nullopt, band).inside_corridor);
  const OngoingBand short_band{{{0.09, 0.0, 0.09}}, 0.9};
  EXPECT_THROW(evaluate_ongoing(path, corridor, 1.0, std::nullopt, short_band),
               std::invalid_argument);
}

TEST(Ongoing, TheBandVerdictTurnsWithTheWorld) {
  // The same question rotated by 90 deg clockwise (x, y) -> (y, -x): the same verdicts, the
  // ellipse's axis turned with it.
  const TimedPath path{{0.0, 0.0, 0.0}, {10.0, 0.0, 10.0}};
  const TimedPath turned{{0.0, 0.0, 0.0}, {10.0, 10.0, 0.0}};
  const OngoingBand band{{{0.09, 0.0, 0.09}, {4.0, 0.0, 0.09}}, 0.9};
  const OngoingBand turned_band{{{0.09, 0.0, 0.09}, {0.09, 0.0, 4.0}}, 0.9};
  for (const Point m : {Point{2.0, 5.0}, Point{-3.5, 4.0}, Point{0.3, 6.0}, Point{0.0, 4.2}}) {
    const auto a = evaluate_ongoing(path, {}, 5.0, m, band);
    const auto b = evaluate_ongoing(turned, {}, 5.0, Point{m.y_m, -m.x_m}, turned_band);
    ASSERT_TRUE(a.inside_corridor && b.inside_corridor);
    EXPECT_EQ(*a.inside_corridor, *b.inside_corridor) << m.x_m << ", " << m.y_m;
    EXPECT_NEAR(a.band_ellipse->major_m, b.band_ellipse->major_m, 1e-9);
    EXPECT_NEAR(std::fmod(a.band_ellipse->major_axis_deg + 90.0, 180.0),
                b.band_ellipse->major_axis_deg, 1e-9);
  }
}

}  // namespace
