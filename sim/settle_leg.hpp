#pragma once
// The settle leg before a commanded maneuver: hold a course at a speed until the vehicle is
// steady by the mission's ConditionSet (at least min_settle_s, at most max_settle_s), so that a
// maneuver starts from the steady state the CKT assumes. `avk sim turn` and the encounter bench
// settle with it.

#include <optional>

#include "mission/condition_set.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::sim {

struct SettleRule {
  double min_settle_s = 20.0;
  double max_settle_s = 300.0;
  double speed_tolerance_mps = 0.05;
  double max_yaw_rate_dps = 1.0;
};

class SettleLeg {
 public:
  // Without a held course the heading is not tested (ConditionSetMonitor).
  SettleLeg(const SettleRule& rule, double speed_mps,
            std::optional<double> held_course_deg = std::nullopt, double start_s = 0.0);

  void update(const vehicle::NavSample& nav);
  // A navigation sample was seen, and the leg is steady after min_settle_s or max_settle_s passed.
  bool done(double now_s) const;
  // The newest navigation sample fed.
  const std::optional<vehicle::NavSample>& newest() const { return newest_; }

 private:
  SettleRule rule_;
  double start_s_;
  mission::ConditionSetMonitor steady_;
  std::optional<vehicle::NavSample> newest_;
};

}  // namespace avk::sim
