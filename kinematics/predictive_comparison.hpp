#pragma once
// The fair comparison: every method predicts each turn of a cell from data that turn is not part
// of, and is scored against that held-out turn.
//
// The thesis' comparison (prediction_comparison.hpp, kept for Figures 5-7 and 5-8) scores AVK
// in-sample, as the spread of a cell's turns about their own mean, and scores the model against
// that mean, a target AVK helped to make. Here, for each turn of a cell:
// - AVK predicts it with the mean of the cell's *other* turns (leave-one-out);
// - the model and the instantaneous assumption predict it as they always do (neither is built
//   from the cell's turns: the model is identified on its own missions);
// and each prediction is scored against the held-out turn, by two metrics:
// - path distance: mean distance at equal arc length (path_metric.hpp), in metres, the default;
// - the thesis' y(x) MSE, in m², both paths extended along the goal heading to the larger x.
// The cell's score is the mean and spread over its held-out turns. The same leave-one-out
// measures the AVK corridor: the share of each held-out turn's points inside the band built
// from the other turns.

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/prediction_comparison.hpp"

namespace avk::kinematics {

struct HeldOutScores {
  std::vector<double> path_m;     // per held-out turn, in the cell's turn order
  std::vector<double> yx_mse_m2;  // per held-out turn
  MeanSd path() const { return mean_sd(path_m); }
  MeanSd yx_mse() const { return mean_sd(yx_mse_m2); }
};

struct PredictiveCell {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;
  std::size_t n_turns = 0;
  double span_m = 0.0;  // the longest turn of the cell: every path is compared over [0, span]
  HeldOutScores avk, instantaneous;
  std::optional<HeldOutScores> model;
  // Leave-one-out coverage of the AVK corridor of `corridor_share`; cells with >= 3 turns (the
  // band needs two turns besides the held-out one).
  std::optional<Coverage> coverage;
};

struct PredictiveOptions {
  std::size_t min_turns = 2;  // leave-one-out needs one turn to predict from
  double station_step_m = kStationStep_m;
  double yx_step_m = 0.01;  // the thesis' x grid
  double corridor_share = kDefaultCorridorShare;
};

// One entry per cell holding at least min_turns turns, row-major as Ckt::cells. The model, when
// given, is asked once per cell. Throws std::invalid_argument, naming the cell, for a model
// prediction with fewer than 2 points or a non-finite one.
std::vector<PredictiveCell> compare_predictive(const Ckt& table, const TurnPredictor* model,
                                               const PredictiveOptions& options = {});

// The thesis' y(x) MSE of two normalised paths, NaN where y(x) cannot be read (a path that
// never gets past x = 0 by a grid step: a small turn that barely left its lead-in).
double yx_mse_or_nan(const Polyline& a, const Polyline& b, double goal_dheading_deg, double step_m);

// Metric selectors for summaries.
enum class PathMetric { path_distance, yx_mse };
const HeldOutScores* held_out_scores(const PredictiveCell& cell, PredictionMethod method);
// Median over cells of the cell means; empty when no cell has the method.
std::optional<double> median_held_out(const std::vector<PredictiveCell>& cells,
                                      PredictionMethod method, PathMetric metric);
// Coverage summed over cells with at least min_turns turns.
Coverage total_coverage(const std::vector<PredictiveCell>& cells, std::size_t min_turns);

}  // namespace avk::kinematics
