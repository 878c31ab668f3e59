#include "mission/turn_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::mission {

double completion_threshold_deg(const CompletionRule& rule, double goal_dheading_deg) {
  const double relative = rule.fraction * std::abs(goal_dheading_deg);
  return std::min(rule.threshold_deg, std::max(rule.floor_deg, relative));
}

TurnMonitor::TurnMonitor(const vehicle::NavSample& start, double commanded_speed_mps,
                         double goal_dheading_deg, const CompletionRule& completion)
    : commanded_speed_mps_(commanded_speed_mps),
      goal_dheading_deg_(goal_dheading_deg),
      threshold_deg_(completion_threshold_deg(completion, goal_dheading_deg)),
      goal_heading_deg_(kinematics::wrap360_deg(start.heading_deg + goal_dheading_deg)),
      // Errors are signed towards the turn, so the goal starts ahead for either side.
      previous_error_deg_(std::abs(goal_dheading_deg)) {
  t_.push_back(start.t_s);
  x_.push_back(start.x_m);
  y_.push_back(start.y_m);
  heading_.push_back(start.heading_deg);
  speed_.push_back(start.speed_mps);
}

Completion TurnMonitor::update(const vehicle::NavSample& nav) {
  if (completion_ != Completion::none) return completion_;
  t_.push_back(nav.t_s);
  x_.push_back(nav.x_m);
  y_.push_back(nav.y_m);
  heading_.push_back(nav.heading_deg);
  speed_.push_back(nav.speed_mps);
  // Error signed towards the turn: positive while the goal is still ahead.
  const double sign = goal_dheading_deg_ < 0.0 ? -1.0 : 1.0;
  const double error = sign * kinematics::angle180_deg(goal_heading_deg_ - nav.heading_deg);
  if (std::abs(error) <= threshold_deg_) {
    completion_ = Completion::within_threshold;
  } else if (previous_error_deg_ > 0.0 && error < 0.0 && error > -90.0) {
    completion_ = Completion::passed_goal;
  }
  previous_error_deg_ = error;
  return completion_;
}

kinematics::TurnSequence TurnMonitor::build(const std::string& vehicle_id,
                                            const std::string& mission_id) const {
  kinematics::TurnMeta meta;
  meta.vehicle_id = vehicle_id;
  meta.mission_id = mission_id;
  meta.commanded_speed_mps = commanded_speed_mps_;
  meta.goal_dheading_deg = goal_dheading_deg_;
  return kinematics::TurnSequence::from_streams(meta, t_, x_, y_, heading_, speed_);
}

}  // namespace avk::mission
