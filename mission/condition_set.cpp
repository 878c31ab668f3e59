#include "mission/condition_set.hpp"

#include <cmath>
#include <numeric>

#include "kinematics/angles.hpp"

namespace avk::mission {

ConditionSetMonitor::ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps,
                                         std::optional<double> held_course_deg)
    : config_(config),
      target_speed_mps_(target_speed_mps),
      held_course_deg_(held_course_deg),
      slope_(config.yaw_rate_window_s) {}

void ConditionSetMonitor::reset(double target_speed_mps, std::optional<double> held_course_deg) {
  target_speed_mps_ = target_speed_mps;
  held_course_deg_ = held_course_deg;
  previous_.reset();
  slope_.reset();
  rates_dps_.clear();
  set_ = false;
}

std::optional<double> ConditionSetMonitor::yaw_rate_dps() const {
  if (config_.yaw_rate_method == YawRateMethod::least_squares) return slope_.rate_dps();
  // Eq. 4.2 over a full window: one calm pair of samples is not a steady course.
  if (rates_dps_.size() < static_cast<std::size_t>(config_.window)) return std::nullopt;
  return std::accumulate(rates_dps_.begin(), rates_dps_.end(), 0.0) /
         static_cast<double>(rates_dps_.size());
}

std::optional<double> ConditionSetMonitor::heading_error_deg() const {
  if (!held_course_deg_ || !previous_) return std::nullopt;
  return kinematics::angle180_deg(previous_->heading_deg - *held_course_deg_);
}

bool ConditionSetMonitor::update(const vehicle::NavSample& nav) {
  if (config_.yaw_rate_method == YawRateMethod::least_squares) {
    slope_.add(nav.t_s, nav.heading_deg);
  } else if (previous_ && nav.t_s > previous_->t_s) {
    // Eq. 4.1, wrap-aware: 359° -> 1° is +2°, not −358°.
    rates_dps_.push_back(kinematics::angle180_deg(nav.heading_deg - previous_->heading_deg) /
                         (nav.t_s - previous_->t_s));
    while (rates_dps_.size() > static_cast<std::size_t>(config_.window))
      rates_dps_.pop_front();
  }
  previous_ = nav;
  const auto rate = yaw_rate_dps();
  const auto error = heading_error_deg();
  set_ = rate && std::abs(*rate) <= config_.max_yaw_rate_dps &&
         std::abs(nav.speed_mps - target_speed_mps_) <= config_.speed_tolerance_mps &&
         (!error || std::abs(*error) <= config_.max_heading_error_deg);
  return set_;
}

}  // namespace avk::mission
