#pragma once
// Does taking the current into account improve predictions? A table learned in the missions of
// one current predicts the turns of missions flown in another:
//   uncompensated: the table built from the turns over ground, as navigated, predicts over ground;
//   compensated:   the table built from the turns in the water frame (their mission's current
//                  removed) predicts through the water, and the drift of the test mission's own
//                  estimated current is added.
// Both are timed by the table's recorded timing and scored with the path metric
// (kinematics/path_metric.hpp: mean distance at equal clock stations) over each test turn's span.
// The test turns are never part of the table.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/current_estimate.hpp"

namespace avk::app {

class Context;

struct CompensatedTurn {
  std::int64_t turn_id = 0;
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // signed as flown
  double uncompensated_m = 0.0;
  double compensated_m = 0.0;
};

struct CompensationComparison {
  std::vector<std::int64_t> table_missions;
  std::vector<std::int64_t> test_missions;
  std::size_t table_turns = 0;
  std::size_t table_water_turns = 0;  // of table_turns, in the water frame
  // The current of each test mission that the compensated prediction adds.
  std::vector<std::pair<std::int64_t, kinematics::CurrentEstimate>> test_currents;
  std::vector<CompensatedTurn> turns;   // the test turns the table could answer
  std::size_t turns_outside_table = 0;  // test turns at a speed the table does not hold
  double uncompensated_mean_m = 0.0;
  double compensated_mean_m = 0.0;
  double improvement() const;  // 1 - compensated / uncompensated
};

// invalid_argument naming "missions" or "test_missions" when either is empty or they overlap;
// not_found for an unknown mission, a table without turns, or a test mission whose current
// cannot be estimated (its why_not).
Result<CompensationComparison> compare_current_compensation(
    Context& ctx, const std::string& vehicle_id, const std::vector<std::int64_t>& table_missions,
    const std::vector<std::int64_t>& test_missions);

}  // namespace avk::app
