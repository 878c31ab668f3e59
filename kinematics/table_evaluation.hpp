#pragma once
// A table judged on turns it was not built from: turns flown after it (other missions, other
// speeds and heading changes, between its cells), each predicted by the table's own query at
// the turn's commanded speed and heading change, by the model, and by the instantaneous ray, and
// scored by path distance at equal arc length (path_metric.hpp) and the thesis' y(x) MSE.
// Interpolation is judged here: a turn between cells is answered by a blend of cells that never
// saw it.

#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/predictive_comparison.hpp"

namespace avk::kinematics {

struct TestCell {
  double speed_mps = 0.0;     // commanded
  double dheading_deg = 0.0;  // |goal|
  std::size_t n_turns = 0;
  bool on_grid = false;  // the table has a cell with turns at this speed and heading change
  double span_m = 0.0;   // the longest test turn: each turn is compared over its cell's span
  HeldOutScores avk, instantaneous;
  std::optional<HeldOutScores> model;
};

// Test turns (ok ones; any frame) grouped by commanded speed (within 0.01 m/s) and |goal| (within
// 0.1°), ordered by speed then heading change. Turns whose speed is outside the table's range
// are skipped (the table does not answer them). The model is asked once per cell.
std::vector<TestCell> evaluate_table(const Ckt& table, const std::vector<TurnSequence>& test_turns,
                                     const TurnPredictor* model,
                                     const PredictiveOptions& options = {});

}  // namespace avk::kinematics
