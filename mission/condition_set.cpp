#include "mission/condition_set.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "kinematics/angles.hpp"

namespace avk::mission {

ConditionSetMonitor::ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps,
                                         std::optional<double> held_course_deg)
    : config_(config), target_speed_mps_(target_speed_mps), held_course_deg_(held_course_deg) {}

void ConditionSetMonitor::reset(double target_speed_mps, std::optional<double> held_course_deg) {
  target_speed_mps_ = target_speed_mps;
  held_course_deg_ = held_course_deg;
  previous_.reset();
  rates_dps_.clear();
  averages_dps_.clear();
  set_ = false;
}

std::optional<double> ConditionSetMonitor::yaw_rate_dps() const {
  if (rates_dps_.empty()) return std::nullopt;
  return std::accumulate(rates_dps_.begin(), rates_dps_.end(), 0.0) /
         static_cast<double>(rates_dps_.size());
}

std::optional<double> ConditionSetMonitor::heading_error_deg() const {
  if (!held_course_deg_ || !previous_) return std::nullopt;
  return kinematics::angle180_deg(previous_->heading_deg - *held_course_deg_);
}

bool ConditionSetMonitor::update(const vehicle::NavSample& nav) {
  const auto window = static_cast<std::size_t>(config_.window);
  if (previous_ && nav.t_s > previous_->t_s) {
    rates_dps_.push_back(kinematics::angle180_deg(nav.heading_deg - previous_->heading_deg) /
                         (nav.t_s - previous_->t_s));
    while (rates_dps_.size() > window)
      rates_dps_.pop_front();
    // A full window is needed: one calm pair of samples is not a steady course.
    if (rates_dps_.size() == window) {
      averages_dps_.push_back(*yaw_rate_dps());
      while (averages_dps_.size() > window)
        averages_dps_.pop_front();
    }
  }
  previous_ = nav;
  const auto error = heading_error_deg();
  set_ = averages_dps_.size() == window &&
         std::all_of(averages_dps_.begin(), averages_dps_.end(),
                     [&](double r) { return std::abs(r) <= config_.max_yaw_rate_dps; }) &&
         std::abs(nav.speed_mps - target_speed_mps_) <= config_.speed_tolerance_mps &&
         (!error || std::abs(*error) <= config_.max_heading_error_deg);
  return set_;
}

}  // namespace avk::mission
