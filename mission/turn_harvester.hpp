#pragma once
// Turns harvested from an ordinary navigation log: every step of the desired
// heading is judged by the rules of a measured turn — the ConditionSet held before it (steady
// yaw rate and speed over the window, the desired heading held), the goal constant until
// completion (the mission's completion rule), not an instantaneous turn (turn_anomaly). The
// judging is TurnExtractor's; the harvester counts every step, marks the turns it accepts as
// harvested with their quality, and leaves out steps a collection mission already recorded.
// Pure: rows in, turns and counts out. docs/harvest.md.

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "mission/step_rejection.hpp"
#include "mission/turn_extractor.hpp"
#include "vehicle/alog.hpp"

namespace avk::mission {

struct HarvestOptions {
  TurnExtractorOptions extraction;
  // A step whose start is within this of a recorded turn's start is that turn: skipped.
  double same_start_tolerance_s = 1e-3;
};

struct HarvestedTurn {
  kinematics::TurnSequence turn;  // status ok, source harvested, quality set
  StepStart start;
};

struct HarvestResult {
  std::size_t steps = 0;             // every step of the desired heading in the log
  std::size_t already_recorded = 0;  // steps whose turn the mission already holds
  std::vector<HarvestedTurn> turns;
  std::array<std::size_t, kStepRejectionCount> rejected{};  // by StepRejection
  std::size_t rejected_total() const;
};

// The quality of a harvested turn, in [0, 1]: steadiness before the step times the cleanness
// of its completion,
//   steady   = 1 - 0.5 min(1, |r| / r_max) - 0.5 min(1, |u - u_d| / u_tol)
//   complete = 1 - 0.5 min(1, | |observed| - |goal| | / threshold(goal))
// with r the moving-average yaw rate and u - u_d the speed error at the step, r_max and u_tol
// the ConditionSet's limits, threshold the mission's completion threshold for the goal. A turn
// from a dead-steady course that ends on its goal scores 1; one at the edge of every limit 0.
double turn_quality(const StepStart& start, const kinematics::TurnSequence& turn,
                    const ConditionSetConfig& condition_set, const CompletionRule& completion);

// Harvests the log (time order). recorded_start_times_s: start times of the turns already stored
// for the log's mission (collection turns of any status, turns of an earlier harvest).
HarvestResult harvest_turns(std::span<const vehicle::GuidedNav> log,
                            std::span<const double> recorded_start_times_s,
                            const HarvestOptions& options, const std::string& vehicle_id,
                            const std::string& mission_id);

}  // namespace avk::mission
