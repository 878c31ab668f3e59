#include "app/current_tracker.hpp"
#include "app/store_access.hpp"

#include <algorithm>

#include "app/current.hpp"
#include "app/mission_legs.hpp"
#include "app/vehicle_motion.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {
// Navigation kept beyond the leg: a little slack so the leg's first rows are still there.
constexpr double kRecentSlackS = 2.0;
}  // namespace

CurrentTracker::CurrentTracker(store::Store& store, std::int64_t mission_id, Publish publish)
    : store_(store), mission_id_(mission_id), publish_(std::move(publish)) {}

void CurrentTracker::nav(const store::NavRow& row) {
  recent_.push_back(row);
  while (!recent_.empty() &&
         recent_.front().t_s < row.t_s - std::max(kSteadyLegS, kMotionLegMaxS) - kRecentSlackS)
    recent_.pop_front();
}

void CurrentTracker::turn_commanded(double t_s) {
  const std::vector<store::NavRow> rows(recent_.begin(), recent_.end());
  auto stretch = steady_stretches_before({t_s}, rows);
  if (!stretch.empty()) motion_legs_.push_back(std::move(stretch.front()));
  auto leg = steady_legs_before({t_s}, rows);
  if (leg.empty()) return;
  legs_.push_back(std::move(leg.front()));
  const auto r = kin::estimate_current(legs_);
  if (!r.estimate) return;
  estimate_ = r.estimate;
  const LegMotion motion = leg_motion(motion_legs_, estimate_);
  speed_reference_ = motion.speed_reference;
  drift_scatter_ = motion.drift_scatter;
  save(t_s);
}

void CurrentTracker::turn_stored(std::int64_t id, const kin::TurnSequence& raw,
                                 kin::TurnStatus status) {
  if (status != kin::TurnStatus::ok) return;
  ok_turns_.emplace_back(id, raw);
  if (estimate_ && current_is_significant(*estimate_))
    save(raw.samples().empty() ? 0.0 : raw.samples().back().t_s);
}

void CurrentTracker::save(double t_s) {
  store::StoredCurrent sc;
  sc.mission_id = mission_id_;
  sc.t_s = t_s;
  sc.method = "legs";
  sc.estimate = *estimate_;
  sc.speed_reference = speed_reference_;
  sc.drift_scatter = drift_scatter_;
  const auto water = current_is_significant(*estimate_)
                         ? water_frame_turns(ok_turns_, water_current(*estimate_))
                         : std::vector<std::pair<std::int64_t, kin::TurnSequence>>{};
  try {
    sc.revision = store_.currents().save(sc, water);
  } catch (const store::StoreUnavailable&) {
    // The database server is away: this estimate is not kept (the next one replaces it anyway,
    // with every turn stored by then).
    return;
  }
  if (publish_) publish_(view_of(sc));
}

}  // namespace avk::app
