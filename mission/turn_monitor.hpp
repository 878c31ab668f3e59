#pragma once
// The turn recorder of pDynamicsMonitor (thesis §4.3, §4.5): notes the start (heading, speed,
// time, goal), records every navigation sample, and decides completion — within the threshold
// of the goal, or when the heading passes the goal between two samples (§4.4.3: at low helm rates
// the vehicle overshot the threshold unseen and the thesis recorded garbage).

#include <optional>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

enum class Completion { none, within_threshold, passed_goal };

class TurnMonitor {
 public:
  // start: the sample at which the new heading was commanded.
  TurnMonitor(const vehicle::NavSample& start, double commanded_speed_mps, double goal_dheading_deg,
              double completion_threshold_deg);

  Completion update(const vehicle::NavSample& nav);
  Completion completion() const { return completion_; }
  double goal_heading_deg() const { return goal_heading_deg_; }
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
