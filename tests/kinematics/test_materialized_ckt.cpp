// The fine table between its rows and columns: it must answer what the table itself
// answers there (Ckt::query), not the nearest fine cell.
#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;

namespace {

// 3 noisy turns a cell of the thesis' grid (10..160 deg x 0.5, 1.0, 1.5 m/s).
const Ckt& table() {
  static const Ckt t = Ckt::build(avk::testing::thesis_grid_turns(3, 0.1, 0.05));
  return t;
}

// A point at a fraction of a polyline's arc length.
Point at_fraction(const Polyline& line, const std::vector<double>& s, double fraction) {
  const double target = fraction * s.back();
  std::size_t i = 1;
  while (i + 1 < s.size() && s[i] < target)
    ++i;
  const double seg = s[i] - s[i - 1];
  const double t = seg > 0.0 ? (target - s[i - 1]) / seg : 0.0;
  return {line[i - 1].x_m + t * (line[i].x_m - line[i - 1].x_m),
          line[i - 1].y_m + t * (line[i].y_m - line[i - 1].y_m)};
}

// Largest distance between two paths at equal fraction of their arc length.
double max_distance_at_equal_fraction_m(const Polyline& a, const Polyline& b) {
  const auto sa = cumulative_arc_length_m(a);
  const auto sb = cumulative_arc_length_m(b);
  double worst = 0.0;
  for (int k = 0; k <= 400; ++k) {
    const double f = k / 400.0;
    worst = std::max(worst, distance_m(at_fraction(a, sa, f), at_fraction(b, sb, f)));
  }
  return worst;
}

double final_heading_deg(const Polyline& line) {
  const Point& a = line[line.size() - 2];
  const Point& b = line.back();
  return heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
}

struct Gap {
  double path_m = 0.0;
  double advance_m = 0.0;
  double transfer_m = 0.0;
};

Gap gap(const TurnPrediction& p, const TurnPrediction& truth) {
  return {max_distance_at_equal_fraction_m(p.trajectory, truth.trajectory),
          std::abs(p.advance_m - truth.advance_m), std::abs(p.transfer_m - truth.transfer_m)};
}

}  // namespace

TEST(MaterializedCkt, BetweenRowsAndColumnsAnswersWhatTheTableAnswers) {
  const MaterializedCkt m(table());
  double worst_snapped_advance_m = 0.0;
  double worst_snapped_path_m = 0.0;
  for (double u : {0.75, 1.25, 0.83, 1.47}) {
    for (double d : {55.5, 100.0, 12.3, -133.7, 172.25}) {
      const TurnPrediction truth = table().query(u, d);
      const TurnPrediction got = m.query(u, d);
      // The nearest fine cell, as query answered before.
      const TurnPrediction& near = *m.lookup(u, d).right_turn;
      TurnPrediction snapped = near;
      if (d < 0.0) snapped.trajectory = reflect_x(snapped.trajectory);

      const Gap g = gap(got, truth);
      const Gap s = gap(snapped, truth);
      SCOPED_TRACE(::testing::Message()
                   << u << " m/s, " << d << " deg: path " << g.path_m << " m (snapped " << s.path_m
                   << " m), advance " << g.advance_m << " m (snapped " << s.advance_m << " m)");
      EXPECT_EQ(got.speed_mps, u);
      EXPECT_EQ(got.dheading_deg, d);
      EXPECT_LT(g.advance_m, 0.01);
      EXPECT_LT(g.transfer_m, 0.01);
      // Both answers are thinned to the table's 5 cm; the blended one from thinned fine cells.
      EXPECT_LT(g.path_m, 0.1);
      EXPECT_NEAR(
          angle180_deg(final_heading_deg(got.trajectory) - final_heading_deg(truth.trajectory)),
          0.0, 0.05);
      EXPECT_EQ(got.exact_cell, truth.exact_cell);
      EXPECT_EQ(got.extrapolated, truth.extrapolated);
      worst_snapped_advance_m = std::max(worst_snapped_advance_m, s.advance_m);
      worst_snapped_path_m = std::max(worst_snapped_path_m, s.path_m);
    }
  }
  // The nearest fine cell, as query answered before, was off by decimetres here (measured: up to
  // 0.15 m of advance, 0.28 m of path; the blend up to 0.1 mm and 6 cm).
  EXPECT_GT(worst_snapped_advance_m, 0.1);
  EXPECT_GT(worst_snapped_path_m, 0.2);
}

TEST(MaterializedCkt, OnAFineGridPointTheAnswerIsThatCell) {
  const MaterializedCkt m(table());
  for (double u : {0.5, 0.8, 1.0, 1.5}) {
    for (double d : {-160.0, -73.0, 40.0, 100.0, 180.0}) {
      const TurnPrediction q = m.query(u, d);
      const TurnPrediction& cell = *m.lookup(u, d).right_turn;
      EXPECT_EQ(q.trajectory, d < 0.0 ? reflect_x(cell.trajectory) : cell.trajectory);
      EXPECT_EQ(q.exact_cell, cell.exact_cell);
      EXPECT_EQ(q.advance_m, cell.advance_m);
    }
  }
  EXPECT_TRUE(m.query(1.0, 100.0).exact_cell);
  EXPECT_FALSE(m.query(1.0, 100.5).exact_cell);
  EXPECT_FALSE(m.query(1.02, 100.0).exact_cell);
}

TEST(MaterializedCkt, SmallHeadingChangesBlendTowardsStraightAhead) {
  const MaterializedCkt m(table());
  for (double d : {0.3, 0.5, 2.5, 9.5}) {
    const TurnPrediction got = m.query(1.0, d);
    const TurnPrediction truth = table().query(1.0, d);
    EXPECT_TRUE(got.extrapolated) << d;  // below the table's 10 deg
    EXPECT_NEAR(final_heading_deg(got.trajectory), d, 0.05) << d;
    EXPECT_LT(max_distance_at_equal_fraction_m(got.trajectory, truth.trajectory), 0.1) << d;
  }
}

TEST(MaterializedCkt, ALastRowShorterThanAStepIsARowOfItsOwn) {
  // Speeds 0.5..1.55: the 0.1 m/s rows stop at 1.5, and 1.55 gets a row so that 1.53 is a blend.
  auto turns = avk::testing::thesis_grid_turns(1, 0.1, 0.0);
  for (auto& t : turns) {
    if (t.meta().commanded_speed_mps == 1.5) t.meta().commanded_speed_mps = 1.55;
  }
  const Ckt t = Ckt::build(turns);
  const MaterializedCkt m(t);
  EXPECT_EQ(m.speed_count(), 12u);
  EXPECT_DOUBLE_EQ(m.row_speed_mps(11), 1.55);
  EXPECT_EQ(m.query(1.55, 70.0).trajectory, t.query(1.55, 70.0).trajectory);
  EXPECT_NEAR(m.query(1.53, 70.0).advance_m, t.query(1.53, 70.0).advance_m, 0.01);
}
