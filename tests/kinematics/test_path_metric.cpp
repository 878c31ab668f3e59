// The path metric at equal arc length, the leave-one-out comparison and the corridor, against
// hand-made paths whose answers are known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/path_metric.hpp"
#include "kinematics/predictive_comparison.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;

namespace {

StationedPath straight(double heading_deg, double length_m, double step_m = 0.1) {
  Polyline p;
  const double h = deg_to_rad(heading_deg);
  for (double s = 0.0; s <= length_m + 1e-9; s += step_m)
    p.push_back({s * std::sin(h), s * std::cos(h)});
  return stationed_by_length(p);
}

StationedPath shifted(StationedPath p, double dx, double dy) {
  for (auto& q : p.points) {
    q.x_m += dx;
    q.y_m += dy;
  }
  return p;
}

}  // namespace

TEST(PathMetric, IdenticalPathsAreZeroApartAndAnOffsetIsItsLength) {
  const StationedPath a = stationed_by_length(avk::testing::circular_arc(5.0, 90.0, 0.05));
  EXPECT_DOUBLE_EQ(mean_path_distance_m(a, a, 90.0, 10.0), 0.0);
  // Translated by (0.3, -0.4): 0.5 m apart at every station, past the end too (both continue
  // along the same goal heading).
  EXPECT_NEAR(mean_path_distance_m(a, shifted(a, 0.3, -0.4), 90.0, 12.0), 0.5, 1e-9);
}

TEST(PathMetric, ARotatedLineDivergesLinearlyWithArcLength) {
  // Two straight lines from the origin, 10° apart: at station s they are 2 s sin(5°) apart, so
  // the mean over s in [0, S] on a uniform grid is S sin(5°).
  const StationedPath a = straight(0.0, 20.0), b = straight(10.0, 20.0);
  EXPECT_NEAR(mean_path_distance_m(a, b, 0.0, 20.0, 0.05), 20.0 * std::sin(deg_to_rad(5.0)), 1e-6);
}

TEST(PathMetric, APathEndingEarlyIsExtendedAlongItsGoalHeading) {
  avk::testing::ArcTurnSpec spec;
  spec.dheading_deg = 60.0;
  spec.lead_in_m = 2.0;
  spec.radius_m = 4.0;
  spec.tail_m = 6.0;
  spec.dt_s = 0.05;
  const TurnSequence longer = avk::testing::make_arc_turn(spec);
  spec.tail_m = 0.0;
  const TurnSequence shorter = avk::testing::make_arc_turn(spec);
  const StationedPath a = stationed_by_time(longer), b = stationed_by_time(shorter);
  EXPECT_GT(a.length_m(), b.length_m() + 5.0);
  // The shorter one continued along 60° is the longer one: apart only by where its last sample
  // fell (the last sample is clamped to the arc's end, at most one 5 cm step from its clock).
  EXPECT_LT(mean_path_distance_m(a, b, 60.0, a.length_m()), 0.05);
  // The instantaneous ray is not.
  EXPECT_GT(mean_path_distance_m(a, instantaneous_path(), 60.0, a.length_m()), 1.0);
}

TEST(PathMetric, StationsComeFromTheClockSoNoiseDoesNotStretchThePath) {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = 1.5;
  spec.dheading_deg = 90.0;
  spec.dt_s = 0.1;
  spec.position_noise_m = 0.3;
  const TurnSequence noisy = avk::testing::make_arc_turn(spec);
  const StationedPath p = stationed_by_time(noisy);
  const double duration = noisy.samples().back().t_s - noisy.samples().front().t_s;
  EXPECT_NEAR(p.length_m(), 1.5 * duration, 1e-9);
  // The zigzag polyline is several times longer than the path the boat went.
  EXPECT_GT(stationed_by_length(p.points).length_m(), 2.0 * p.length_m());
}

TEST(PathMetric, TheMeanOfMirroredOffsetsIsTheMiddlePath) {
  const StationedPath mid = straight(30.0, 10.0);
  const std::vector<StationedPath> pair{shifted(mid, 0.2, 0.0), shifted(mid, -0.2, 0.0)};
  const StationedPath mean = mean_path_at_stations(pair, 30.0);
  EXPECT_LT(mean_path_distance_m(mean, mid, 30.0, 10.0), 1e-9);
}

TEST(PathMetric, BadSpansAndStepsAreRefused) {
  const StationedPath a = straight(0.0, 1.0);
  EXPECT_THROW(mean_path_distance_m(a, a, 0.0, -1.0), std::invalid_argument);
  EXPECT_THROW(mean_path_distance_m(a, a, 0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(mean_path_distance_m(a, a, 0.0, 1e12, 0.05), std::invalid_argument);
  EXPECT_THROW(stationed_by_length({}), std::invalid_argument);
}

TEST(PredictiveComparison, LeaveOneOutPredictsEachTurnFromTheOthers) {
  // Three turns of one cell: two alike, one with a longer lead-in. Held out, the odd one is
  // predicted by the mean of the two alike (its distance to them), and each of the alike ones
  // by the mean of its twin and the odd one: half that far at every station.
  std::vector<TurnSequence> turns;
  for (double lead : {2.0, 2.0, 3.0}) {
    avk::testing::ArcTurnSpec s;
    s.dheading_deg = 90.0;
    s.lead_in_m = lead;
    s.radius_m = 3.0;
    s.dt_s = 0.1;
    turns.push_back(avk::testing::make_arc_turn(s));
  }
  const Ckt table = Ckt::build(turns);
  const auto cells = compare_predictive(table, nullptr);
  ASSERT_EQ(cells.size(), 1u);
  const PredictiveCell& c = cells[0];
  ASSERT_EQ(c.avk.path_m.size(), 3u);
  const StationedPath alike = stationed_by_time(turns[0]), odd = stationed_by_time(turns[2]);
  const double apart = mean_path_distance_m(alike, odd, 90.0, c.span_m);
  EXPECT_GT(apart, 0.3);
  EXPECT_NEAR(c.avk.path_m[2], apart, 1e-9);
  EXPECT_NEAR(c.avk.path_m[0], 0.5 * apart, 1e-9);
  EXPECT_NEAR(c.avk.path_m[1], 0.5 * apart, 1e-9);
  EXPECT_NEAR(c.avk.path().mean, 2.0 * apart / 3.0, 1e-9);
  // The ray is scored against the same held-out turns.
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(
        c.instantaneous.path_m[i],
        mean_path_distance_m(instantaneous_path(), stationed_by_time(turns[i]), 90.0, c.span_m),
        1e-12);
  EXPECT_FALSE(c.model.has_value());
}

TEST(PredictiveComparison, IdenticalTurnsArePredictedExactly) {
  std::vector<TurnSequence> turns(4, avk::testing::make_arc_turn({}));
  const auto cells = compare_predictive(Ckt::build(turns), nullptr);
  ASSERT_EQ(cells.size(), 1u);
  for (double d : cells[0].avk.path_m)
    EXPECT_NEAR(d, 0.0, 1e-12);
  for (double m : cells[0].avk.yx_mse_m2)
    EXPECT_NEAR(m, 0.0, 1e-12);
}

TEST(Corridor, FactorIsTheStudentPredictionInterval) {
  // t_{0.95, 4} = 2.1318; √(1 + 1/5) = 1.0954.
  EXPECT_NEAR(corridor_factor(5, 0.9), 2.1318 * 1.0954, 2e-3);
  // Two turns know little: t_{0.95, 1} = 6.3138, √1.5.
  EXPECT_NEAR(corridor_factor(2, 0.9), 6.3138 * std::sqrt(1.5), 2e-3);
  EXPECT_THROW(corridor_factor(1, 0.9), std::invalid_argument);
  EXPECT_THROW(corridor_factor(5, 1.0), std::invalid_argument);
}

TEST(Corridor, SpreadOfParallelOffsetsIsTheirStandardDeviation) {
  const StationedPath mid = straight(0.0, 10.0);
  std::vector<StationedPath> turns;
  for (double dx : {-0.3, -0.1, 0.1, 0.3})
    turns.push_back(shifted(mid, dx, 0.0));
  const StationedPath mean = mean_path_at_stations(turns, 0.0);
  const auto c = corridor_of(turns, mean, 0.0);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->n_turns, 4u);
  const double sd = std::sqrt((0.09 + 0.01 + 0.01 + 0.09) / 3.0);
  for (double v : c->lateral_sd_m)
    EXPECT_NEAR(v, sd, 1e-9);
  // The band about the mean: the offsets to either side are the half width, right of north is +x.
  const CorridorBand band = corridor_band(mean.points, *c, 0.9);
  EXPECT_NEAR(band.half_width_m[3], corridor_factor(4, 0.9) * sd, 1e-9);
  EXPECT_NEAR(band.right[3].x_m - mean.points[3].x_m, band.half_width_m[3], 1e-9);
  EXPECT_NEAR(band.left[3].x_m - mean.points[3].x_m, -band.half_width_m[3], 1e-9);
}

TEST(Corridor, NominalNinetyPercentHoldsNinetyPercentOfGaussianTurnsLeftOut) {
  // Cells of 6 turns that fan out from a common course: turn i ends e_i ~ N(0, 0.5 m) to the
  // side after 20 m, growing linearly. At every station the offsets are Gaussian, so the
  // leave-one-out band of 90 % must hold ~90 % of the held-out points.
  std::mt19937 rng(42);
  std::normal_distribution<double> offset(0.0, 0.5);
  Coverage total;
  for (int cell = 0; cell < 200; ++cell) {
    std::vector<StationedPath> turns;
    for (int i = 0; i < 6; ++i) {
      const double e = offset(rng);
      StationedPath p;
      for (int k = 0; k <= 200; ++k) {
        const double s = 0.1 * k;
        p.s_m.push_back(s);
        p.points.push_back({e * s / 20.0, s});
      }
      turns.push_back(std::move(p));
    }
    for (std::size_t i = 0; i < turns.size(); ++i) {
      std::vector<StationedPath> others;
      for (std::size_t j = 0; j < turns.size(); ++j)
        if (j != i) others.push_back(turns[j]);
      const StationedPath mean = mean_path_at_stations(others, 0.0);
      const auto c = corridor_of(others, mean, 0.0);
      ASSERT_TRUE(c);
      total += corridor_coverage(turns[i], mean, *c, 0.0, 0.9);
    }
  }
  EXPECT_GT(total.share(), 0.86);
  EXPECT_LT(total.share(), 0.94);
}

TEST(Corridor, CellsCarryItAndQueriesBlendIt) {
  const auto turns = avk::testing::thesis_grid_turns(5, 0.1, 0.2);
  const Ckt table = Ckt::build(turns);
  for (const auto& c : table.cells()) {
    ASSERT_TRUE(c.corridor) << c.speed_mps << " " << c.dheading_deg;
    EXPECT_EQ(c.corridor->n_turns, 5u);
  }
  const TurnPrediction on = table.query(1.0, 70.0);
  ASSERT_TRUE(on.corridor);
  EXPECT_EQ(*on.corridor, *table.cell(1, 2).corridor);
  const TurnPrediction between = table.query(0.75, 55.0);
  ASSERT_TRUE(between.corridor);
  // A blend of four cells: its spread at mid-length lies within theirs.
  double lo = 1e9, hi = 0.0;
  for (std::size_t i : {0u, 1u})
    for (std::size_t j : {1u, 2u}) {
      lo = std::min(lo, table.cell(i, j).corridor->lateral_sd_m[50]);
      hi = std::max(hi, table.cell(i, j).corridor->lateral_sd_m[50]);
    }
  EXPECT_GE(between.corridor->lateral_sd_m[50], lo - 1e-12);
  EXPECT_LE(between.corridor->lateral_sd_m[50], hi + 1e-12);
  // The fine table guidance asks carries it too, between its rows as on them.
  const MaterializedCkt fine(table);
  const TurnPrediction f = fine.query(0.75, 55.5);
  ASSERT_TRUE(f.corridor);
  EXPECT_EQ(f.corridor->n_turns, 5u);
  EXPECT_NEAR(f.corridor->lateral_sd_m[50], table.query(0.75, 55.5).corridor->lateral_sd_m[50],
              0.05 * hi + 1e-9);
}
