#pragma once
// A vehicle's CKT over (speed, heading change, initial yaw rate) (kinematics/ckt3.hpp):
// built from its stored turns, the cells no turn reached filled by its black-box yaw model
// started at the slice's yaw rate, with the coverage and, where a cell has both measured turns
// and a model turn, how far the model's path lies from the measured ones.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/ckt3.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::app {

class Context;

struct YawRateTableOptions {
  // Slice yaw rates (deg/s, + into the turn); none: 0 and the clusters of the turns' rates.
  std::optional<std::vector<double>> yaw_rates_dps;
  kinematics::YawRateCktOptions match{};
  bool fill_with_model = true;           // needs a stored model of the vehicle
  std::optional<std::int64_t> model_id;  // none: the vehicle's latest
  bool check_model = false;              // fill model_checks (simulates every measured cell)
};

// Where a cell has measured turns: the mean path distance (path_metric.hpp, equal arc length
// over the longest turn) of the turns from the model's turn for the cell and, for reference,
// from the cell's own (measured) trajectory.
struct ModelCellCheck {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;
  double initial_yaw_rate_dps = 0.0;
  std::size_t n_turns = 0;
  double model_error_m = 0.0;
  double table_error_m = 0.0;
};

struct YawRateTable {
  kinematics::YawRateCkt table;
  kinematics::YawRateBuildReport report;
  std::optional<std::int64_t> model_id;  // the model that filled cells
  std::vector<kinematics::SliceCoverage> coverage;
  std::vector<ModelCellCheck> model_checks;  // empty without a model
};

// The model's normalised right turn for a cell as a turn record (status ok, normalised, the
// initial yaw rate set), sampled at the model's rate; empty when the model cannot hold the rate.
std::optional<kinematics::TurnSequence> model_cell_turn(const kinematics::YawModel& model,
                                                        double speed_mps, double dheading_deg,
                                                        double initial_yaw_rate_dps);

// not_found when the vehicle has no ok turns.
Result<YawRateTable> vehicle_yaw_rate_table(Context& ctx, const std::string& vehicle_id,
                                            const YawRateTableOptions& options = {});

}  // namespace avk::app
