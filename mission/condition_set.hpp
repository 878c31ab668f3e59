#pragma once
// ConditionSet (thesis §4.4.1): a turn starts only from a steady course at the target speed.
// Yaw rate comes from differenced headings (wrap-aware, eq. 4.1) smoothed by a moving average
// (eq. 4.2), because differenced compass headings are far too noisy on their own.

#include <deque>
#include <optional>

#include "mission/mission_config.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

class ConditionSetMonitor {
 public:
  ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps);

  // Feeds one navigation sample; true once speed and smoothed yaw rate are both within limits.
  bool update(const vehicle::NavSample& nav);
  bool conditions_set() const { return set_; }
  double target_speed_mps() const { return target_speed_mps_; }
  std::optional<double> yaw_rate_dps() const;  // moving average; empty until two samples
  void reset(double target_speed_mps);

 private:
  ConditionSetConfig config_;
  double target_speed_mps_;
  std::optional<vehicle::NavSample> previous_;
  std::deque<double> rates_dps_;
  bool set_ = false;
};

}  // namespace avk::mission
