#include "sim/settle_leg.hpp"

namespace avk::sim {

SettleLeg::SettleLeg(const SettleRule& rule, double speed_mps,
                     std::optional<double> held_course_deg, double start_s)
    : rule_(rule),
      start_s_(start_s),
      steady_({.speed_tolerance_mps = rule.speed_tolerance_mps,
               .max_yaw_rate_dps = rule.max_yaw_rate_dps,
               .window = 5,
               .timeout_s = rule.max_settle_s,
               .max_heading_error_deg = mission::ConditionSetConfig{}.max_heading_error_deg},
              speed_mps, held_course_deg) {}

void SettleLeg::update(const vehicle::NavSample& nav) {
  steady_.update(nav);
  newest_ = nav;
}

bool SettleLeg::done(double now_s) const {
  if (!newest_) return false;
  const double held = now_s - start_s_;
  return (held >= rule_.min_settle_s && steady_.conditions_set()) || held >= rule_.max_settle_s;
}

}  // namespace avk::sim
