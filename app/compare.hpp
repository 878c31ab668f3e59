#pragma once
// The fair comparison of prediction methods (thesis §5.2): per cell, the CKT (AVK), the yaw
// model and the instantaneous-turn assumption, each scored against the cell's observed turns.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

struct CompareQuery {
  std::string vehicle_id;
  std::vector<std::int64_t> missions;    // whose ok turns are scored; empty: all the vehicle's
  std::optional<std::int64_t> model_id;  // none: the vehicle's latest model, if it has one
  bool without_model = false;            // score AVK and instantaneous only
  double completion_threshold_deg = 5.0;
};

struct Comparison {
  std::string vehicle_id;
  std::optional<store::StoredModel> model;
  kinematics::Ckt table;
  std::vector<kinematics::CellComparison> cells;
};

// not_found for a model id that does not exist or a vehicle without ok turns in the missions.
Result<Comparison> compare(Context& ctx, const CompareQuery& q);

}  // namespace avk::app
