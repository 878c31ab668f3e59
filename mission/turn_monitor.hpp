#pragma once
// The turn recorder of pDynamicsMonitor (thesis §4.3, §4.5): notes the start (heading, speed,
// time, goal), records every navigation sample, and decides completion — within the completion
// threshold of the goal (relative to the commanded change, CompletionRule), or when the heading
// passes the goal between two samples (§4.4.3: at low helm rates the vehicle overshot the
// threshold unseen and the thesis recorded garbage).

#include <optional>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

// The heading error under which a turn of goal_dheading_deg (either sign) is complete:
// max(floor, min(threshold, fraction x |goal|)), and never above the threshold (a threshold set
// below the floor bounds it). The one place the rule is computed: the mission, `avk sim turn`,
// the alog extractor and turn_anomaly all ask here, so they agree on when a turn ended.
double completion_threshold_deg(const CompletionRule& rule, double goal_dheading_deg);

enum class Completion { none, within_threshold, passed_goal };

class TurnMonitor {
 public:
  // start: the sample at which the new heading was commanded.
  TurnMonitor(const vehicle::NavSample& start, double commanded_speed_mps, double goal_dheading_deg,
              const CompletionRule& completion);

  Completion update(const vehicle::NavSample& nav);
  Completion completion() const { return completion_; }
  double goal_heading_deg() const { return goal_heading_deg_; }
  double threshold_deg() const { return threshold_deg_; }  // the rule applied to this goal
  std::size_t sample_count() const { return t_.size(); }

  // The raw TurnSequence (status ok); validation is the caller's (it decides ok/rejected).
  kinematics::TurnSequence build(const std::string& vehicle_id,
                                 const std::string& mission_id) const;

 private:
  double commanded_speed_mps_;
  double goal_dheading_deg_;
  double threshold_deg_;
  double goal_heading_deg_;
  double previous_error_deg_;
  Completion completion_ = Completion::none;
  std::vector<double> t_, x_, y_, heading_, speed_;
};

}  // namespace avk::mission
