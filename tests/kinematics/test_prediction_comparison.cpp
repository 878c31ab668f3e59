#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/turn_metrics.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::arc_turn_length_m;
using avk::testing::arc_turn_point;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

ArcTurnSpec arc(double speed_mps, double dheading_deg, double lead_in_m, double radius_m,
                unsigned seed = 1, double noise_m = 0.0) {
  ArcTurnSpec s;
  s.speed_mps = speed_mps;
  s.dheading_deg = dheading_deg;
  s.lead_in_m = lead_in_m;
  s.radius_m = radius_m;
  s.dt_s = 0.1;
  s.position_noise_m = noise_m;
  s.seed = seed;
  s.start = {3.0 * seed, -2.0 * seed, 23.0 * seed};
  return s;
}

// The analytic normalised turn of a spec, every 0.05 m of arc length, ending on the goal.
Polyline analytic(const ArcTurnSpec& s) {
  Polyline out;
  const double total = arc_turn_length_m(s);
  for (double d = 0.0; d < total; d += 0.05)
    out.push_back(arc_turn_point(s, d, nullptr));
  out.push_back(arc_turn_point(s, total, nullptr));
  return out;
}

// A turn from piecewise-straight normalised points, recorded from the origin heading north with
// the heading of each leg.
TurnSequence polyline_turn(const Polyline& pts, double goal_deg, double speed_mps = 1.0) {
  TurnMeta meta;
  // Strings moved in, not assigned from literals: GCC 12 at -O3 warns falsely (-Wrestrict) on
  // assigning a short literal here.
  meta.vehicle_id = std::string("test");
  meta.mission_id = std::string("m");
  meta.commanded_speed_mps = speed_mps;
  meta.goal_dheading_deg = goal_deg;
  std::vector<TurnSample> samples;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point& a = pts[i == 0 ? 0 : i - 1];
    const Point& b = pts[i];
    const double h = i == 0 ? 0.0 : heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
    samples.push_back({static_cast<double>(i), b.x_m, b.y_m, h, speed_mps});
  }
  TurnSequence t(meta, samples);
  t.fill_derived_metadata();
  return t;
}

// The same turn recorded as its mirror image about the initial course: a left turn.
TurnSequence mirrored(const TurnSequence& t) {
  TurnMeta meta = t.meta();
  meta.goal_dheading_deg = -meta.goal_dheading_deg;
  const Pose start{t.samples().front().x_m, t.samples().front().y_m, meta.initial_heading_deg};
  std::vector<TurnSample> samples = t.samples();
  for (TurnSample& s : samples) {
    const Point local = normalize_point({s.x_m, s.y_m}, start, TurnSide::right);
    const Point w = place_normalized({local}, start, TurnSide::left).front();
    s.x_m = w.x_m;
    s.y_m = w.y_m;
    s.heading_deg = wrap360_deg(2.0 * start.heading_deg - s.heading_deg);
  }
  TurnSequence out(meta, samples);
  out.fill_derived_metadata();
  return out;
}

CellComparison only(const std::vector<CellComparison>& cells) {
  EXPECT_EQ(cells.size(), 1u);
  return cells.empty() ? CellComparison{} : cells.front();
}

void expect_same(const MethodError& a, const MethodError& b, const std::string& what) {
  EXPECT_NEAR(a.mse_m2, b.mse_m2, 1e-9) << what;
  EXPECT_EQ(a.improvement_pct.has_value(), b.improvement_pct.has_value()) << what;
  if (a.improvement_pct && b.improvement_pct) {
    EXPECT_NEAR(*a.improvement_pct, *b.improvement_pct, 1e-7) << what;
  }
  EXPECT_NEAR(a.advance_error_m, b.advance_error_m, 1e-9) << what;
  EXPECT_NEAR(a.transfer_error_m, b.transfer_error_m, 1e-9) << what;
}

}  // namespace

TEST(PredictionComparison, IdenticalTurnsAndAModelThatPredictsTheMean) {
  std::vector<TurnSequence> turns;
  for (unsigned seed = 1; seed <= 3; ++seed)
    turns.push_back(make_arc_turn(arc(1.0, 90.0, 2.0, 3.0, seed)));
  const Ckt table = Ckt::build(turns);
  const CellComparison first = only(compare_predictions(table, nullptr));
  EXPECT_EQ(first.n_turns, 3u);
  EXPECT_NEAR(first.avk.mse_m2, 0.0, 1e-18);
  EXPECT_FALSE(first.model.has_value());
  ASSERT_TRUE(first.avk.improvement_pct.has_value());
  EXPECT_NEAR(*first.avk.improvement_pct, 100.0, 1e-12);
  EXPECT_FALSE(first.instantaneous.improvement_pct.has_value());
  EXPECT_NEAR(first.avk.advance_error_m, 0.0, 1e-9);
  EXPECT_NEAR(first.avk.transfer_error_m, 0.0, 1e-9);
  // The instantaneous turn pivots on the spot: its errors are the whole advance and transfer.
  EXPECT_NEAR(first.instantaneous.advance_error_m, 2.0 + 3.0, 1e-9);
  EXPECT_NEAR(first.instantaneous.transfer_error_m, 3.0, 1e-9);
  EXPECT_GT(first.instantaneous.mse_m2, 1.0);
  EXPECT_TRUE(std::none_of(first.outlier.begin(), first.outlier.end(), [](bool b) { return b; }));
  EXPECT_FALSE(first.without_outliers.has_value());

  const Polyline mean_points = first.mean.points();
  const TurnPredictor model = [&](double, double) { return mean_points; };
  const CellComparison c = only(compare_predictions(table, &model));
  ASSERT_TRUE(c.model.has_value());
  EXPECT_NEAR(c.model->mse_m2, 0.0, 1e-20);
  ASSERT_TRUE(c.model->improvement_pct.has_value());
  EXPECT_NEAR(*c.model->improvement_pct, 100.0, 1e-12);
  // The mean's last grid point is the end of the turn (x = R at 90 deg).
  EXPECT_NEAR(c.model->transfer_error_m, 0.0, 0.01);
  EXPECT_NEAR(c.model->advance_error_m, 0.0, 1e-9);
}

TEST(PredictionComparison, AModelPredictingTheInstantaneousTurnGainsNothing) {
  std::vector<TurnSequence> turns;
  for (unsigned seed = 1; seed <= 4; ++seed)
    turns.push_back(make_arc_turn(arc(1.0, 70.0, 2.0, 2.5 + 0.3 * seed, seed, 0.05)));
  const Ckt table = Ckt::build(turns);
  // One metre along the goal ray: the goal-ray extension carries it on along the same line.
  const TurnPredictor ray = [](double, double dheading_deg) {
    const double g = deg_to_rad(dheading_deg);
    return Polyline{{0.0, 0.0}, {std::sin(g), std::cos(g)}};
  };
  const CellComparison c = only(compare_predictions(table, &ray));
  ASSERT_TRUE(c.model.has_value());
  EXPECT_NEAR(c.model->mse_m2, c.instantaneous.mse_m2, 1e-9);
  ASSERT_TRUE(c.model->improvement_pct.has_value());
  EXPECT_NEAR(*c.model->improvement_pct, 0.0, 1e-6);
  EXPECT_LT(c.avk.mse_m2, c.instantaneous.mse_m2);
  EXPECT_GT(*c.avk.improvement_pct, 90.0);
}

TEST(PredictionComparison, StraightLineTurnsByHand) {
  // Two "turns" at 90 deg: a lead-in of 1 m or 3 m, then due east to x = 4. On the 1 cm grid
  // (401 points) y is 0 at x = 0 (the start) and the lead-in beyond, so the mean is 2 there.
  const Ckt table = Ckt::build({polyline_turn({{0, 0}, {0, 1}, {4, 1}}, 90.0),
                                polyline_turn({{0, 0}, {0, 3}, {4, 3}}, 90.0)});
  const TurnPredictor model = [](double, double) { return Polyline{{0, 0}, {0, 1.5}, {4, 1.5}}; };
  const CellComparison c = only(compare_predictions(table, &model));
  ASSERT_EQ(c.mean.y_m.size(), 401u);
  EXPECT_NEAR(c.mean.y_m[0], 0.0, 1e-12);
  EXPECT_NEAR(c.mean.y_m[200], 2.0, 1e-12);
  const double frac = 400.0 / 401.0;
  ASSERT_EQ(c.per_turn_mse_m2.size(), 2u);
  EXPECT_NEAR(c.per_turn_mse_m2[0], 1.0 * frac, 1e-12);
  EXPECT_NEAR(c.per_turn_mse_m2[1], 1.0 * frac, 1e-12);
  EXPECT_NEAR(c.avk.mse_m2, 1.0 * frac, 1e-12);
  // The 90-deg ray is y = 0 (to cot(90 deg) ~ 6e-17).
  EXPECT_NEAR(c.instantaneous.mse_m2, 4.0 * frac, 1e-12);
  ASSERT_TRUE(c.model.has_value());
  EXPECT_NEAR(c.model->mse_m2, 0.25 * frac, 1e-12);
  EXPECT_NEAR(*c.avk.improvement_pct, 75.0, 1e-9);
  EXPECT_NEAR(*c.model->improvement_pct, 93.75, 1e-9);
  // Advances 1 and 3 (mean 2), transfers 4 and 4.
  EXPECT_NEAR(c.avk.advance_error_m, 1.0, 1e-12);
  EXPECT_NEAR(c.avk.transfer_error_m, 0.0, 1e-12);
  EXPECT_NEAR(c.instantaneous.advance_error_m, 2.0, 1e-12);
  EXPECT_NEAR(c.instantaneous.transfer_error_m, 4.0, 1e-12);
  EXPECT_NEAR(c.model->advance_error_m, 0.5, 1e-12);
  EXPECT_NEAR(c.model->transfer_error_m, 0.0, 1e-12);
}

TEST(PredictionComparison, AdvanceAndTransferErrorsOnArcs) {
  // Advance L + R sin(60), transfer R (1 - cos 60) = R / 2, for R = 3 and 5 after L = 2.
  const double s60 = std::sin(deg_to_rad(60.0));
  const Ckt table = Ckt::build(
      {make_arc_turn(arc(1.0, 60.0, 2.0, 3.0, 1)), make_arc_turn(arc(1.0, 60.0, 2.0, 5.0, 2))});
  const TurnPredictor model = [](double u, double d) { return analytic(arc(u, d, 2.0, 3.0)); };
  const CellComparison c = only(compare_predictions(table, &model));
  const double mean_advance = 2.0 + 4.0 * s60, mean_transfer = 2.0;
  EXPECT_NEAR(c.avk.advance_error_m, s60, 1e-9);
  EXPECT_NEAR(c.avk.transfer_error_m, 0.5, 1e-9);
  EXPECT_NEAR(c.instantaneous.advance_error_m, mean_advance, 1e-9);
  EXPECT_NEAR(c.instantaneous.transfer_error_m, mean_transfer, 1e-9);
  ASSERT_TRUE(c.model.has_value());
  EXPECT_NEAR(c.model->advance_error_m, s60, 1e-9);
  EXPECT_NEAR(c.model->transfer_error_m, 0.5, 1e-9);
  // The model is one of the two turns, so it is as far from the mean as that turn.
  // (Sampled differently: 5 cm of arc against 10 cm, so only to a percent.)
  EXPECT_NEAR(c.model->mse_m2, c.per_turn_mse_m2[0], 0.01 * c.per_turn_mse_m2[0]);
}

TEST(PredictionComparison, OutlierTurnIsFlaggedAndLeftOut) {
  std::vector<TurnSequence> turns;
  // 40 deg: six similar turns and one with twice the radius; 100 deg: six similar turns only.
  for (unsigned seed = 1; seed <= 6; ++seed) {
    turns.push_back(make_arc_turn(arc(1.0, 40.0, 2.0, 3.0 + 0.05 * (seed % 3), seed, 0.01)));
    turns.push_back(make_arc_turn(arc(1.0, 100.0, 2.0, 3.0 + 0.05 * (seed % 3), seed, 0.01)));
  }
  turns.push_back(make_arc_turn(arc(1.0, 40.0, 2.0, 6.0, 99, 0.01)));
  const Ckt table = Ckt::build(turns);
  const auto cells = compare_predictions(table, nullptr);
  ASSERT_EQ(cells.size(), 2u);

  const CellComparison& with = cells[0];
  EXPECT_EQ(with.dheading_deg, 40.0);
  ASSERT_EQ(with.n_turns, 7u);
  ASSERT_EQ(with.outlier.size(), 7u);
  // Build keeps the input order within a cell, so the outlier is the last turn.
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_FALSE(with.outlier[i]) << i;
  EXPECT_TRUE(with.outlier[6]);
  ASSERT_TRUE(with.without_outliers.has_value());
  EXPECT_EQ(with.without_outliers->n_turns, 6u);
  EXPECT_LT(with.without_outliers->avk.mse_m2, 0.2 * with.avk.mse_m2);
  EXPECT_LT(with.without_outliers->avk.advance_error_m, with.avk.advance_error_m);
  EXPECT_FALSE(with.without_outliers->model.has_value());

  const CellComparison& similar = cells[1];
  EXPECT_EQ(similar.dheading_deg, 100.0);
  for (bool b : similar.outlier)
    EXPECT_FALSE(b);
  EXPECT_FALSE(similar.without_outliers.has_value());

  // The summary helpers take the without-outliers result where there is one.
  EXPECT_EQ(method_error(with, PredictionMethod::avk, true), &with.without_outliers->avk);
  EXPECT_EQ(method_error(similar, PredictionMethod::avk, true), &similar.avk);
  EXPECT_EQ(method_error(with, PredictionMethod::model), nullptr);
  EXPECT_NEAR(*median_mse_m2(cells, PredictionMethod::avk),
              0.5 * (with.avk.mse_m2 + similar.avk.mse_m2), 1e-15);
  EXPECT_NEAR(*median_mse_m2(cells, PredictionMethod::avk, true),
              0.5 * (with.without_outliers->avk.mse_m2 + similar.avk.mse_m2), 1e-15);
  EXPECT_FALSE(median_mse_m2(cells, PredictionMethod::model).has_value());
  EXPECT_FALSE(median_improvement_pct(cells, PredictionMethod::instantaneous).has_value());
}

TEST(PredictionComparison, OutlierAfterRemovalNeedsMinTurns) {
  // Four similar turns and an outlier: left out, only 4 remain; with min_turns 5 there is nothing
  // to report without the outlier even though it is flagged.
  std::vector<TurnSequence> turns;
  for (unsigned seed = 1; seed <= 4; ++seed)
    turns.push_back(make_arc_turn(arc(1.0, 40.0, 2.0, 3.0, seed, 0.02)));
  turns.push_back(make_arc_turn(arc(1.0, 40.0, 2.0, 8.0, 9, 0.02)));
  const Ckt table = Ckt::build(turns);
  ComparisonOptions o;
  const CellComparison c = only(compare_predictions(table, nullptr, o));
  ASSERT_TRUE(c.outlier[4]);
  ASSERT_TRUE(c.without_outliers.has_value());
  o.min_turns = 5;
  const CellComparison strict = only(compare_predictions(table, nullptr, o));
  EXPECT_TRUE(strict.outlier[4]);
  EXPECT_FALSE(strict.without_outliers.has_value());
}

TEST(PredictionComparison, RobustOutliersByHand) {
  // Median 3, MAD 1: z(100) = 0.6745 * 97, z(4) = 0.6745.
  EXPECT_EQ(robust_outliers({1, 2, 3, 4, 100}, 3.5),
            (std::vector<bool>{false, false, false, false, true}));
  // Only the high side: a turn unusually close to the mean is not suspect.
  EXPECT_EQ(robust_outliers({100, 100.5, 99.5, 101, 99, 0}, 3.5), std::vector<bool>(6, false));
  // MAD = 0 flags nothing, nor does a MAD at or below the floor.
  EXPECT_EQ(robust_outliers({1, 1, 1, 50}, 3.5), std::vector<bool>(4, false));
  EXPECT_EQ(robust_outliers({1e-32, 2e-32, 3e-32, 1e-30}, 3.5),
            (std::vector<bool>{false, false, false, true}));
  EXPECT_EQ(robust_outliers({1e-32, 2e-32, 3e-32, 1e-30}, 3.5, 1e-12), std::vector<bool>(4, false));
  EXPECT_TRUE(robust_outliers({}, 3.5).empty());
  EXPECT_EQ(*median_of({3, 1, 2}), 2.0);
  EXPECT_EQ(*median_of({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(*median_of({std::numeric_limits<double>::quiet_NaN(), 5.0}), 5.0);
  EXPECT_FALSE(median_of({}).has_value());
}

TEST(PredictionComparison, CellsWithTooFewTurnsAreSkipped) {
  const Ckt table = Ckt::build({make_arc_turn(arc(1.0, 40.0, 2.0, 3.0, 1)),
                                make_arc_turn(arc(1.0, 90.0, 2.0, 3.0, 2)),
                                make_arc_turn(arc(1.0, 90.0, 2.0, 3.5, 3))});
  ASSERT_EQ(table.cells().size(), 2u);
  const CellComparison c = only(compare_predictions(table, nullptr));
  EXPECT_EQ(c.dheading_deg, 90.0);
  EXPECT_EQ(c.n_turns, 2u);

  ComparisonOptions one;
  one.min_turns = 1;
  const auto both = compare_predictions(table, nullptr, one);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].avk.mse_m2, 0.0);  // a single turn is its own mean

  // A table loaded from file keeps no turns.
  std::vector<CktCell> cells = table.cells();
  for (CktCell& cell : cells)
    cell.turns.clear();
  const Ckt loaded = Ckt::from_cells(table.grid(), cells, table.options());
  EXPECT_TRUE(compare_predictions(loaded, nullptr, one).empty());
}

TEST(PredictionComparison, BadModelOutputNamesTheCell) {
  const Ckt table = Ckt::build(
      {make_arc_turn(arc(1.5, 70.0, 2.0, 3.0, 1)), make_arc_turn(arc(1.5, 70.0, 2.0, 3.5, 2))});
  const TurnPredictor nan_model = [](double, double) {
    return Polyline{{0, 0}, {0, 1}, {std::numeric_limits<double>::quiet_NaN(), 2}};
  };
  const TurnPredictor empty_model = [](double, double) { return Polyline{}; };
  for (const TurnPredictor* m : {&nan_model, &empty_model}) {
    try {
      compare_predictions(table, m);
      ADD_FAILURE() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("1.5 m/s"), std::string::npos) << what;
      EXPECT_NE(what.find("70 deg"), std::string::npos) << what;
    }
  }
}

TEST(PredictionComparison, LeftTurnsCompareAsTheirMirroredRightTurns) {
  std::vector<TurnSequence> right, left;
  unsigned seed = 1;
  for (double d : {40.0, 130.0}) {
    for (int r = 0; r < 5; ++r, ++seed) {
      right.push_back(make_arc_turn(arc(1.0, d, 1.5, 2.5 + 0.2 * r, seed, 0.05)));
      left.push_back(mirrored(right.back()));
    }
  }
  right.push_back(make_arc_turn(arc(1.0, 130.0, 1.5, 7.0, 50, 0.05)));  // an outlier too
  left.push_back(mirrored(right.back()));
  ASSERT_LT(left.front().meta().goal_dheading_deg, 0.0);
  const TurnPredictor model = [](double u, double d) { return analytic(arc(u, d, 1.0, 2.0)); };
  const auto a = compare_predictions(Ckt::build(right), &model);
  const auto b = compare_predictions(Ckt::build(left), &model);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string cell = std::to_string(a[i].dheading_deg);
    EXPECT_EQ(a[i].dheading_deg, b[i].dheading_deg);
    EXPECT_EQ(a[i].n_turns, b[i].n_turns);
    EXPECT_EQ(a[i].outlier, b[i].outlier) << cell;
    ASSERT_EQ(a[i].mean.y_m.size(), b[i].mean.y_m.size());
    for (std::size_t k = 0; k < a[i].mean.y_m.size(); ++k)
      ASSERT_NEAR(a[i].mean.y_m[k], b[i].mean.y_m[k], 1e-9) << cell << " " << k;
    for (std::size_t k = 0; k < a[i].per_turn_mse_m2.size(); ++k)
      EXPECT_NEAR(a[i].per_turn_mse_m2[k], b[i].per_turn_mse_m2[k], 1e-9) << cell;
    expect_same(a[i].avk, b[i].avk, cell + " avk");
    expect_same(a[i].instantaneous, b[i].instantaneous, cell + " instantaneous");
    ASSERT_TRUE(a[i].model && b[i].model);
    expect_same(*a[i].model, *b[i].model, cell + " model");
    ASSERT_EQ(a[i].without_outliers.has_value(), b[i].without_outliers.has_value()) << cell;
    if (a[i].without_outliers) {
      expect_same(a[i].without_outliers->avk, b[i].without_outliers->avk, cell + " w/o avk");
    }
  }
  EXPECT_TRUE(a[1].without_outliers.has_value());
}
