#include "mission/condition_set.hpp"

#include <cmath>
#include <numeric>

#include "kinematics/angles.hpp"

namespace avk::mission {

ConditionSetMonitor::ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps)
    : config_(config), target_speed_mps_(target_speed_mps) {}

void ConditionSetMonitor::reset(double target_speed_mps) {
  target_speed_mps_ = target_speed_mps;
  previous_.reset();
  rates_dps_.clear();
  set_ = false;
}

std::optional<double> ConditionSetMonitor::yaw_rate_dps() const {
  if (rates_dps_.empty()) return std::nullopt;
  return std::accumulate(rates_dps_.begin(), rates_dps_.end(), 0.0) /
         static_cast<double>(rates_dps_.size());
}

bool ConditionSetMonitor::update(const vehicle::NavSample& nav) {
  if (previous_ && nav.t_s > previous_->t_s) {
    rates_dps_.push_back(kinematics::angle180_deg(nav.heading_deg - previous_->heading_deg) /
                         (nav.t_s - previous_->t_s));
    while (rates_dps_.size() > static_cast<std::size_t>(config_.window))
      rates_dps_.pop_front();
  }
  previous_ = nav;
  const auto rate = yaw_rate_dps();
  // A full window is needed: one calm pair of samples is not a steady course.
  set_ = rate && rates_dps_.size() == static_cast<std::size_t>(config_.window) &&
         std::abs(nav.speed_mps - target_speed_mps_) <= config_.speed_tolerance_mps &&
         std::abs(*rate) <= config_.max_yaw_rate_dps;
  return set_;
}

}  // namespace avk::mission
