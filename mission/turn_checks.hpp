#pragma once
// Anomaly checks on a finished turn before it is stored as ok (thesis §4.5: an instantaneous
// "turn", mismatched streams; and what the pass-through completion rule cannot rule out).

#include <optional>
#include <string>

#include "kinematics/turn_sequence.hpp"
#include "mission/mission_config.hpp"
#include "mission/step_rejection.hpp"

namespace avk::mission {

struct TurnCheckOptions {
  CompletionRule completion;      // the rule the turn was recorded under
  double max_sample_gap_s = 2.0;  // a longer gap in navigation leaves the trajectory unknown
};

struct TurnAnomaly {
  StepRejection kind;  // the class of the reason, for counting
  std::string reason;  // what the mission stores as the turn's status reason
};

// Why the turn must be rejected, or empty when it is usable.
std::optional<TurnAnomaly> find_turn_anomaly(const kinematics::TurnSequence& raw,
                                             const TurnCheckOptions& options);

// find_turn_anomaly's reason alone.
std::optional<std::string> turn_anomaly(const kinematics::TurnSequence& raw,
                                        const TurnCheckOptions& options);

}  // namespace avk::mission
