#pragma once
// The fair comparison of prediction methods (thesis §5.2): per cell, the CKT (AVK), the yaw
// model and the instantaneous-turn assumption, each scored against the cell's observed turns.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/model_view.hpp"
#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/predictive_comparison.hpp"
#include "kinematics/speed_change_comparison.hpp"
#include "kinematics/table_evaluation.hpp"

namespace avk::app {

class Context;

struct CompareQuery {
  std::string vehicle_id;
  std::vector<std::int64_t> missions;  // whose ok turns are scored; empty: all the vehicle's
  // Turns to judge the table on, from missions it was not built from (removed from `missions`,
  // or from all the vehicle's missions when that is empty): off-grid speeds and heading changes
  // test its interpolation, on-grid ones its prediction of a new run.
  std::vector<std::int64_t> test_missions;
  std::optional<std::int64_t> model_id;  // none: the vehicle's latest model, if it has one
  bool without_model = false;            // score AVK and instantaneous only
  double completion_threshold_deg = 5.0;
  double corridor_share = kinematics::kDefaultCorridorShare;  // of the AVK corridor's coverage
};

struct Comparison {
  std::string vehicle_id;
  std::optional<ModelView> model;
  kinematics::Ckt table;
  // The thesis' in-sample scoring (Figures 5-7, 5-8): AVK as its turns' spread about their mean.
  std::vector<kinematics::CellComparison> cells;
  // The fair one: every method scored on turns it was not built from (leave-one-out for AVK),
  // by path distance at equal arc length and by the thesis' y(x) MSE.
  std::vector<kinematics::PredictiveCell> predictive;
  // The table judged on the test missions' turns (empty without test missions).
  std::vector<kinematics::TestCell> test_cells;
  // The turns with a speed change among the scored missions' turns, each predictor on turns it
  // was not built from (kinematics/speed_change_comparison.hpp).
  std::vector<kinematics::SpeedChangeCellScores> speed_change;
  double corridor_share = kinematics::kDefaultCorridorShare;
};

// Cells with at least this many turns count for the corridor's coverage (fewer: too few to say).
inline constexpr std::size_t kCoverageMinTurns = 5;

// not_found for a model id that does not exist or a vehicle without ok turns in the missions.
Result<Comparison> compare(Context& ctx, const CompareQuery& q);

}  // namespace avk::app
