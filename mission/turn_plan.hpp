#pragma once
// The turn array unrolled into the ordered list of turns a mission performs (pDynamicsMonitor's
// turn_array), and what is left of it when a mission resumes.

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/geometry.hpp"
#include "mission/mission_config.hpp"

namespace avk::mission {

struct TurnTask {
  std::size_t index = 0;  // position in the full plan
  double speed_mps = 0.0;
  double dheading_deg = 0.0;                 // magnitude, as the cell
  std::optional<kinematics::TurnSide> side;  // empty: chosen at the turn (direction auto)
  int attempts = 0;                          // aborted tries so far
  // Target yaw rate when the turn is commanded, deg/s, + into the turn, - against it; 0: from a
  // steady course (TurnArray::initial_yaw_rates_dps).
  double initial_yaw_rate_dps = 0.0;
  // A speed-change turn (turn_array.speed_changes): speed_mps is u0, held before the turn, and
  // this is u1, commanded with the new heading. Empty: a constant-speed turn.
  std::optional<double> speed_after_mps;
};

// Speed-major, then heading change, then initial yaw rate, then repeats: at each speed the vehicle
// settles once and runs every heading change, as in the thesis' Figure 4-1. `alternate` alternates
// by plan index, so a resumed mission gives each remaining turn the side it had in the original
// plan.
std::vector<TurnTask> plan_turns(const MissionConfig& config);

struct CellCount {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;
  int done = 0;
  std::optional<double> speed_after_mps;  // a speed-change cell
};

// The plan without the turns already done: per cell, the first `done` tasks are dropped.
std::vector<TurnTask> remaining_turns(const std::vector<TurnTask>& plan,
                                      const std::vector<CellCount>& done);

// Cells are matched with the same tolerances the CKT uses (kinematics::within_match): values a
// mission's spacing apart (0.05 m/s, 0.5 deg) are two cells.
bool same_cell(double speed_a_mps, double dheading_a_deg, double speed_b_mps,
               double dheading_b_deg);
// Also the speed after: a speed-change cell is never a constant-speed one.
bool same_cell(double speed_a_mps, std::optional<double> speed_after_a_mps, double dheading_a_deg,
               double speed_b_mps, std::optional<double> speed_after_b_mps, double dheading_b_deg);

}  // namespace avk::mission
