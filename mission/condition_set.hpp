#pragma once
// ConditionSet (thesis §4.4.1): a turn starts only from a steady course at the target speed.
//
// Steady means: the speed within its tolerance, the yaw rate within its limit, and the heading
// within max_heading_error_deg of the held course. The yaw rate is estimated as the config says
// (ConditionSetConfig::yaw_rate_method): by default the least-squares slope of the heading over
// a time window, whose noise for a compass of σ = 1° at 10 Hz is 0.36 °/s over 2 s; the thesis'
// moving average of differenced headings (eqs. 4.1, 4.2) scatters by 2.8 °/s there, so with it
// a 1 °/s limit is met by chance about one sample in four. The heading test is what a rate test
// alone cannot see: at the far end of an overshoot swing the yaw rate passes through zero while
// the vehicle is 10° or more off course.

#include <deque>
#include <optional>

#include "kinematics/yaw_rate_estimator.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

class ConditionSetMonitor {
 public:
  // Without a held course the heading is not tested (a log whose course is not known).
  ConditionSetMonitor(ConditionSetConfig config, double target_speed_mps,
                      std::optional<double> held_course_deg = std::nullopt);

  // Feeds one navigation sample; true once speed, heading and yaw rate are all within their
  // limits.
  bool update(const vehicle::NavSample& nav);
  bool conditions_set() const { return set_; }
  double target_speed_mps() const { return target_speed_mps_; }
  std::optional<double> held_course_deg() const { return held_course_deg_; }
  // The yaw-rate estimate (°/s, + clockwise); empty until the estimator has a full window.
  std::optional<double> yaw_rate_dps() const;
  // Heading of the newest sample minus the held course, in (−180, 180]; empty without either.
  std::optional<double> heading_error_deg() const;
  void reset(double target_speed_mps, std::optional<double> held_course_deg = std::nullopt);

 private:
  ConditionSetConfig config_;
  double target_speed_mps_;
  std::optional<double> held_course_deg_;
  std::optional<vehicle::NavSample> previous_;
  kinematics::YawRateEstimator slope_;
  std::deque<double> rates_dps_;  // moving_average: differenced headings, the newest window
  bool set_ = false;
};

}  // namespace avk::mission
