#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

// A vehicle whose lead-in and radius grow with speed, as a real one's do.
ArcTurnSpec spec_for(double speed_mps, double dheading_deg, unsigned seed = 1) {
  ArcTurnSpec s;
  s.speed_mps = speed_mps;
  s.dheading_deg = dheading_deg;
  s.lead_in_m = 0.5 + 1.0 * speed_mps;
  s.radius_m = 1.0 + 2.0 * speed_mps;
  s.dt_s = 0.1;
  s.seed = seed;
  s.start = {10.0 * seed, -3.0 * seed, 37.0 * seed};
  return s;
}

std::vector<TurnSequence> grid_turns(const std::vector<double>& speeds,
                                     const std::vector<double>& dheadings, int repeats = 2,
                                     double noise_m = 0.0) {
  std::vector<TurnSequence> turns;
  unsigned seed = 1;
  for (double u : speeds) {
    for (double d : dheadings) {
      for (int r = 0; r < repeats; ++r) {
        ArcTurnSpec s = spec_for(u, r % 2 ? -d : d, seed++);
        s.position_noise_m = noise_m;
        turns.push_back(make_arc_turn(s));
      }
    }
  }
  return turns;
}

double final_heading_deg(const Polyline& line) {
  const Point& a = line[line.size() - 2];
  const Point& b = line.back();
  return heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
}

}  // namespace

TEST(Ckt, CellStatisticsMatchTheAnalyticArc) {
  const Ckt t = Ckt::build(grid_turns({1.0}, {40, 90, 150}, 3));
  ASSERT_EQ(t.grid().speeds_mps.size(), 1u);
  ASSERT_EQ(t.grid().dheadings_deg.size(), 3u);
  for (const CktCell& c : t.cells()) {
    const ArcTurnSpec s = spec_for(c.speed_mps, c.dheading_deg);
    const double d = deg_to_rad(c.dheading_deg);
    EXPECT_EQ(c.n_turns, 3u);
    EXPECT_NEAR(c.advance_m.mean, s.lead_in_m + s.radius_m * std::sin(d), 1e-6);
    EXPECT_NEAR(c.transfer_m.mean, s.radius_m * (1 - std::cos(d)), 1e-6);
    EXPECT_NEAR(c.advance_m.sd, 0.0, 1e-6);
    ASSERT_TRUE(c.avk_error_m2.has_value());
    EXPECT_NEAR(*c.avk_error_m2, 0.0, 1e-6);  // identical turns
    ASSERT_GE(c.trajectory.size(), 3u);
    EXPECT_NEAR(final_heading_deg(c.trajectory), c.dheading_deg, 1.0);
  }
}

TEST(Ckt, ExactCellQueryReturnsTheCellAndLeftIsTheMirror) {
  const Ckt t = Ckt::build(grid_turns({0.5, 1.0}, {30, 60, 90}));
  const TurnPrediction r = t.query(1.0, 60.0);
  EXPECT_TRUE(r.exact_cell);
  EXPECT_FALSE(r.extrapolated);
  EXPECT_EQ(r.trajectory, t.cell(1, 1).trajectory);
  const TurnPrediction l = t.query(1.0, -60.0);
  ASSERT_EQ(l.trajectory.size(), r.trajectory.size());
  for (std::size_t i = 0; i < l.trajectory.size(); ++i) {
    EXPECT_DOUBLE_EQ(l.trajectory[i].x_m, -r.trajectory[i].x_m);
    EXPECT_DOUBLE_EQ(l.trajectory[i].y_m, r.trajectory[i].y_m);
  }
  EXPECT_DOUBLE_EQ(l.advance_m, r.advance_m);
  EXPECT_DOUBLE_EQ(l.transfer_m, r.transfer_m);
}

TEST(Ckt, InterpolatedSeventyEndsOnSeventyBetweenItsNeighbours) {
  const Ckt t = Ckt::build(grid_turns({1.0}, {60, 80}));
  const TurnPrediction p = t.query(1.0, 70.0);
  EXPECT_FALSE(p.exact_cell);
  EXPECT_FALSE(p.extrapolated);
  EXPECT_NEAR(final_heading_deg(p.trajectory), 70.0, 1.0);
  const CktCell& c60 = t.cell(0, 0);
  const CktCell& c80 = t.cell(0, 1);
  EXPECT_GT(p.advance_m, std::min(c60.advance_m.mean, c80.advance_m.mean));
  EXPECT_LT(p.advance_m, std::max(c60.advance_m.mean, c80.advance_m.mean));
  EXPECT_GT(p.transfer_m, c60.transfer_m.mean);
  EXPECT_LT(p.transfer_m, c80.transfer_m.mean);
  // The trajectory's own end point lies between the neighbours' trajectory ends too.
  const Point e = p.trajectory.back(), e60 = c60.trajectory.back(), e80 = c80.trajectory.back();
  EXPECT_GT(e.x_m, std::min(e60.x_m, e80.x_m));
  EXPECT_LT(e.x_m, std::max(e60.x_m, e80.x_m));
  // Compared with the analytic 70-degree arc of the same vehicle, the geometry is close.
  const ArcTurnSpec s = spec_for(1.0, 70.0);
  EXPECT_NEAR(p.transfer_m, s.radius_m * (1 - std::cos(deg_to_rad(70.0))), 0.15);
}

TEST(Ckt, DroppingTheObservedTurnsChangesNoAnswer) {
  const Ckt full = Ckt::build(grid_turns({0.5, 1.0, 1.5}, {30, 60, 90, 150}, 3, 0.05));
  Ckt lean = full;
  lean.drop_observed_turns();
  for (const CktCell& c : lean.cells())
    EXPECT_TRUE(c.turns.empty());
  ASSERT_FALSE(full.cells().front().turns.empty());
  // On cells, between rows and columns, to port, and past the heading changes the table holds.
  for (const double u : {0.5, 0.8, 1.0, 1.4})
    for (const double d : {30.0, -45.0, 60.0, 120.0, -150.0, 170.0})
      EXPECT_EQ(lean.query(u, d), full.query(u, d)) << u << " m/s, " << d << " deg";
}

TEST(Ckt, InterpolatesAcrossSpeed) {
  const Ckt t = Ckt::build(grid_turns({0.5, 1.5}, {90}));
  const TurnPrediction p = t.query(1.0, 90.0);
  EXPECT_FALSE(p.exact_cell);
  EXPECT_NEAR(p.advance_m, 0.5 * (t.cell(0, 0).advance_m.mean + t.cell(1, 0).advance_m.mean), 1e-9);
  EXPECT_NEAR(final_heading_deg(p.trajectory), 90.0, 1.0);
  EXPECT_GT(p.transfer_m, t.cell(0, 0).transfer_m.mean);
  EXPECT_LT(p.transfer_m, t.cell(1, 0).transfer_m.mean);
}

TEST(Ckt, IdenticalRowsInterpolateToTheSameTrajectory) {
  // Same turns recorded under two speed labels: blending equal profiles must reproduce the cell.
  // The mean turn is taken at stations of the clock times the commanded speed, so the relabelled
  // row samples the same path at other points: equal to within the fit's resolution.
  auto turns = grid_turns({1.0}, {90});
  auto more = turns;
  for (auto& t : more)
    t.meta().commanded_speed_mps = 2.0;
  turns.insert(turns.end(), more.begin(), more.end());
  const Ckt t = Ckt::build(turns);
  const Polyline& cell = t.cell(0, 0).trajectory;
  const TurnPrediction p = t.query(1.3, 90.0);
  ASSERT_EQ(p.trajectory.size(), cell.size());
  for (std::size_t i = 0; i < cell.size(); ++i) {
    EXPECT_NEAR(p.trajectory[i].x_m - p.trajectory[0].x_m, cell[i].x_m - cell[0].x_m, 1e-3);
    EXPECT_NEAR(p.trajectory[i].y_m - p.trajectory[0].y_m, cell[i].y_m - cell[0].y_m, 1e-3);
  }
}

TEST(Ckt, OutOfRangeSpeedIsAClearErrorNeverExtrapolated) {
  const Ckt t = Ckt::build(grid_turns({0.5, 1.0}, {45}));
  try {
    t.query(1.6, 45.0);
    FAIL() << "expected CktRangeError";
  } catch (const CktRangeError& e) {
    EXPECT_NE(std::string(e.what()).find("1.6"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("0.5-1"), std::string::npos);
  }
  EXPECT_THROW(t.query(0.2, 45.0), CktRangeError);
  EXPECT_THROW(t.query(1.0, 181.0), CktRangeError);
  EXPECT_THROW(t.query(std::nan(""), 45.0), std::invalid_argument);
  EXPECT_THROW(Ckt().query(1.0, 10.0), CktRangeError);
}

TEST(Ckt, HeadingChangesOutsideTheTableAreFlaggedExtrapolations) {
  const Ckt t = Ckt::build(grid_turns({1.0}, {40, 120}));
  const TurnPrediction small = t.query(1.0, 10.0);
  EXPECT_TRUE(small.extrapolated);
  EXPECT_NEAR(final_heading_deg(small.trajectory), 10.0, 1.0);
  const TurnPrediction big = t.query(1.0, -170.0);
  EXPECT_TRUE(big.extrapolated);
  EXPECT_NEAR(angle180_deg(final_heading_deg(big.trajectory) - 190.0), 0.0, 1.5);
  // The lead-in + arc model recovers the analytic arc's advance/transfer far from the table.
  const ArcTurnSpec s = spec_for(1.0, 170.0);
  EXPECT_NEAR(big.transfer_m, s.radius_m * (1 - std::cos(deg_to_rad(170.0))), 1e-3);
  const TurnPrediction zero = t.query(1.0, 0.0);
  EXPECT_NEAR(zero.transfer_m, 0.0, 1e-9);
  EXPECT_NEAR(zero.trajectory.back().x_m, 0.0, 1e-9);
}

TEST(Ckt, EmptyCellsAreBridgedByTheirNeighbours) {
  auto turns = grid_turns({1.0}, {30, 60, 90});
  turns.erase(std::remove_if(turns.begin(), turns.end(),
                             [](const TurnSequence& t) {
                               return std::abs(t.meta().goal_dheading_deg) == 60.0;
                             }),
              turns.end());
  const Ckt t = Ckt::build(turns, {}, CktGrid{{1.0}, {30, 60, 90}});
  EXPECT_FALSE(t.cell(0, 1).has_data());
  const TurnPrediction p = t.query(1.0, 60.0);
  EXPECT_FALSE(p.exact_cell);
  EXPECT_NEAR(final_heading_deg(p.trajectory), 60.0, 1.0);
}

TEST(Ckt, AbortedAndOffGridTurnsAreNotUsed) {
  auto turns = grid_turns({1.0}, {45});
  auto aborted = turns.front();
  aborted.meta().status = TurnStatus::aborted;
  auto off = turns.front();
  off.meta().commanded_speed_mps = 3.0;
  turns.push_back(aborted);
  turns.push_back(off);
  CktBuildReport rep;
  const Ckt t = Ckt::build(turns, {}, CktGrid{{1.0}, {45}}, &rep);
  EXPECT_EQ(rep.turns_used, 2u);
  EXPECT_EQ(rep.turns_skipped_status, 1u);
  EXPECT_EQ(rep.turns_unassigned, 1u);
  EXPECT_EQ(t.cell(0, 0).n_turns, 2u);
}

TEST(Ckt, AdvanceAndTransferGrowWithHeadingChangeAndSpeed) {
  const Ckt t = Ckt::build(grid_turns({0.5, 1.0, 1.5}, {10, 40, 70}));
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 1; j < 3; ++j) {
      EXPECT_GT(t.cell(i, j).transfer_m.mean, t.cell(i, j - 1).transfer_m.mean);
    }
  }
  for (std::size_t j = 0; j < 3; ++j) {
    for (std::size_t i = 1; i < 3; ++i) {
      EXPECT_GT(t.cell(i, j).advance_m.mean, t.cell(i - 1, j).advance_m.mean);
    }
  }
}

TEST(MaterializedCkt, LookupMatchesQueryAtFineGridPoints) {
  const Ckt t = Ckt::build(grid_turns({0.5, 1.0, 1.5}, {10, 40, 70, 100, 130, 160}));
  const MaterializedCkt m(t);
  EXPECT_EQ(m.speed_count(), 11u);
  EXPECT_EQ(m.dheading_count(), 181u);
  for (double u : {0.5, 0.8, 1.5}) {
    for (double d : {-160.0, -73.0, 0.0, 45.0, 100.0, 180.0}) {
      const auto hit = m.lookup(u, d);
      const TurnPrediction q = t.query(u, std::abs(d));
      EXPECT_EQ(hit.right_turn->trajectory, q.trajectory) << u << " " << d;
      EXPECT_EQ(hit.side, d < 0 ? TurnSide::left : TurnSide::right);
    }
  }
  // Nearest fine cell.
  EXPECT_EQ(m.lookup(0.81, 44.6).right_turn, m.lookup(0.8, 45.0).right_turn);
  EXPECT_THROW(m.lookup(1.7, 10.0), CktRangeError);
}

// The cell trajectory (mean -> fit -> piecewise linear) stays on the analytic path it came from.
TEST(Ckt, CellTrajectoryFollowsTheAnalyticPath) {
  const Ckt t = Ckt::build(grid_turns({1.0}, {20, 90, 160}, 2));
  for (const CktCell& c : t.cells()) {
    ArcTurnSpec s = spec_for(c.speed_mps, c.dheading_deg);
    s.tail_m = 20.0;  // the goal ray after the turn
    Polyline truth;
    for (double d = 0.0; d <= avk::testing::arc_turn_length_m(s); d += 0.005) {
      truth.push_back(avk::testing::arc_turn_point(s, d, nullptr));
    }
    double worst = 0.0;
    for (const Point& v : c.trajectory)
      worst = std::max(worst, distance_to_polyline_m(v, truth));
    EXPECT_LT(worst, 0.1) << c.dheading_deg;
    EXPECT_EQ(c.trajectory.front(), (Point{0.0, 0.0}));
  }
}

namespace {

// A normalised right turn to dheading_deg of radius 3 m after a 2 m lead-in, then 1 m along the
// goal heading, drawn from `start` (the lead-in runs north from it).
Polyline right_turn_from(Point start, double dheading_deg) {
  Polyline line{start};
  for (const Point& p : avk::testing::circular_arc(3.0, dheading_deg, 0.3))
    line.push_back({start.x_m + p.x_m, start.y_m + 2.0 + p.y_m});
  const double g = deg_to_rad(dheading_deg);
  line.push_back({line.back().x_m + std::sin(g), line.back().y_m + std::cos(g)});
  return line;
}

// The profile's heading changes, deg.
std::vector<double> changes_deg(const HeadingProfile& hp, double dheading_deg) {
  std::vector<double> out;
  for (double f : hp.fraction)
    out.push_back(f * dheading_deg);
  return out;
}

// Each heading change of the profile lies within 180 deg of the turn's mid-heading.
void expect_within_half_turn_of_mid(const HeadingProfile& hp, double dheading_deg) {
  for (double c : changes_deg(hp, dheading_deg)) {
    EXPECT_GT(c, dheading_deg / 2 - 180.0);
    EXPECT_LE(c, dheading_deg / 2 + 180.0);
  }
}

// The trajectory the profile draws on its own (weight 1), at vertex resolution.
void expect_reproduces(const HeadingProfile& hp, const Polyline& line, double dheading_deg) {
  const Polyline drawn = blended_trajectory({{&hp, 1.0}}, hp.length_m, dheading_deg, 1e-9);
  for (const Point& p : line)
    EXPECT_LT(distance_to_polyline_m(p, drawn), 1e-9);
  EXPECT_LT(distance_m(drawn.back(), line.back()), 1e-9);
}

}  // namespace

// GNSS noise at the start of a slow turn: the mean path first steps 0.3 m backwards. That step
// points south, and the turn that follows is still a turn from north to 160 deg, not to 520.
TEST(HeadingProfile, AShortBackwardFirstSegmentDoesNotWrapTheTurn) {
  Polyline line{{0.0, 0.0}};
  for (const Point& p : right_turn_from({0.0, -0.3}, 160.0))
    line.push_back(p);
  const HeadingProfile hp = heading_profile(line, 160.0);
  const std::vector<double> c = changes_deg(hp, 160.0);
  EXPECT_NEAR(c.front(), 180.0, 1e-9);  // south, on the turn's side of its mid-heading
  EXPECT_NEAR(c[1], 0.0, 1e-9);         // the lead-in runs north again: 0, not 360
  EXPECT_NEAR(c.back(), 160.0, 1e-9);
  expect_within_half_turn_of_mid(hp, 160.0);
  expect_reproduces(hp, line, 160.0);
  // Blended with a clean 130 deg neighbour, it answers 145 deg on 145 deg.
  const Polyline clean = right_turn_from({0.0, 0.0}, 130.0);
  const HeadingProfile hc = heading_profile(clean, 130.0);
  const Polyline mid =
      blended_trajectory({{&hp, 0.5}, {&hc, 0.5}}, 0.5 * (hp.length_m + hc.length_m), 145.0, 0.05);
  EXPECT_NEAR(final_heading_deg(mid), 145.0, 1e-6);
}

// A segment that doubles back in the middle of a turn (heading 70 deg, then 251 deg, then on at
// 110 deg) stays one segment: the turn after it keeps its headings.
TEST(HeadingProfile, ASegmentDoublingBackMidTurnLeavesTheRestInPlace) {
  const auto dir = [](double heading_deg, double length_m) {
    const double h = deg_to_rad(heading_deg);
    return Point{length_m * std::sin(h), length_m * std::cos(h)};
  };
  Polyline line{{0.0, 0.0}};
  for (const auto& [h, len] : std::vector<std::pair<double, double>>{
           {0.0, 2.0}, {35.0, 1.0}, {70.0, 1.0}, {251.0, 0.2}, {110.0, 1.0}, {160.0, 2.0}}) {
    const Point d = dir(h, len);
    line.push_back({line.back().x_m + d.x_m, line.back().y_m + d.y_m});
  }
  const HeadingProfile hp = heading_profile(line, 160.0);
  const std::vector<double> c = changes_deg(hp, 160.0);
  ASSERT_EQ(c.size(), 6u);
  const std::vector<double> expected{0.0, 35.0, 70.0, 251.0, 110.0, 160.0};
  for (std::size_t i = 0; i < c.size(); ++i)
    EXPECT_NEAR(c[i], expected[i], 1e-9) << i;
  expect_reproduces(hp, line, 160.0);
}

// A turn that wobbles left before it turns, or overshoots its goal, keeps the signs of both: the
// window about the mid-heading leaves 90 deg and more on either side of the turn.
TEST(HeadingProfile, AWobbleBeforeAndAnOvershootAfterKeepTheirSigns) {
  for (double d : {10.0, 90.0, 180.0}) {
    Polyline line{{0.0, 0.0}, {-0.5, 1.0}};  // about -27 deg
    for (const Point& p : right_turn_from({-0.5, 1.0}, d + 30.0))
      line.push_back(p);
    const double g = deg_to_rad(d);
    line.push_back({line.back().x_m + std::sin(g), line.back().y_m + std::cos(g)});
    const HeadingProfile hp = heading_profile(line, d);
    const std::vector<double> c = changes_deg(hp, d);
    EXPECT_NEAR(c.front(), rad_to_deg(std::atan2(-0.5, 1.0)), 1e-9) << d;
    EXPECT_NEAR(c[c.size() - 2], d + 30.0, 1e-9) << d;
    EXPECT_NEAR(c.back(), d, 1e-9) << d;
    expect_within_half_turn_of_mid(hp, d);
  }
}
