#pragma once
// ConditionSet (thesis §4.4.1): a turn starts only from a steady course at the target speed.
// Yaw rate comes from differenced headings (wrap-aware, eq. 4.1) smoothed by a moving average
// (eq. 4.2), because differenced compass headings are far too noisy on their own.
//
// Steady means more than a small moving average at one instant: at the far end of an overshoot
// swing the average passes through zero while the vehicle is 10° or more off course. So the
// heading must be within max_heading_error_deg of the held course, and every moving-average
// value of the last window ticks (not just the newest) must be within the yaw-rate limit. The
// single differenced samples are not tested one by one: with 1° compass noise at 10 Hz each of
// them scatters by ~14 °/s, so no window would ever qualify.

#include <deque>
#include <optional>

#include "mission/mission_config.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

class ConditionSetMonitor {
 public:
  // Without a held course the heading is not tested (a log whose course is not known).
  ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps,
                      std::optional<double> held_course_deg = std::nullopt);

  // Feeds one navigation sample; true once speed, heading and smoothed yaw rate are all within
  // their limits.
  bool update(const vehicle::NavSample& nav);
  bool conditions_set() const { return set_; }
  double target_speed_mps() const { return target_speed_mps_; }
  std::optional<double> held_course_deg() const { return held_course_deg_; }
  std::optional<double> yaw_rate_dps() const;  // moving average; empty until two samples
  // Heading of the newest sample minus the held course, in (−180, 180]; empty without either.
  std::optional<double> heading_error_deg() const;
  void reset(double target_speed_mps, std::optional<double> held_course_deg = std::nullopt);

 private:
  ConditionSetConfig config_;
  double target_speed_mps_;
  std::optional<double> held_course_deg_;
  std::optional<vehicle::NavSample> previous_;
  std::deque<double> rates_dps_;     // differenced headings, the newest window
  std::deque<double> averages_dps_;  // moving averages of full windows, the newest window
  bool set_ = false;
};

}  // namespace avk::mission
