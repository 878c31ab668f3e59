#pragma once
// A running mission's current, kept up to date as the mission runs: the steady
// leg before each turn's command joins the evidence and the current is estimated again
// (kinematics/current_estimate.hpp); the estimate is stored with the water-frame form of the
// mission's ok turns so far (when it is significant, app/current.hpp) and handed to whoever shows
// it live. The longer steady stretches before the commands are judged in it too: which speed the
// loop holds and how straight-line predictions scatter (app/vehicle_motion.hpp), stored with it.
// Owned by the mission's recorder, so a mission run from the command line keeps its
// estimate as one run by the server does.

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "app/current_view.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/turn_sequence.hpp"
#include "store/store.hpp"

namespace avk::app {

class CurrentTracker {
 public:
  using Publish = std::function<void(const CurrentView&)>;
  CurrentTracker(store::Store& store, std::int64_t mission_id, Publish publish = {});

  void nav(const store::NavRow& row);
  // A turn's heading was commanded at t_s: the leg before it is evidence.
  void turn_commanded(double t_s);
  // A turn was stored under this id; an ok one gets its water-frame form.
  void turn_stored(std::int64_t id, const kinematics::TurnSequence& raw,
                   kinematics::TurnStatus status);

  const std::optional<kinematics::CurrentEstimate>& estimate() const { return estimate_; }
  const std::optional<kinematics::SpeedReferenceEvidence>& speed_reference() const {
    return speed_reference_;
  }
  const std::optional<kinematics::DriftScatter>& drift_scatter() const { return drift_scatter_; }
  std::size_t legs() const { return legs_.size(); }

 private:
  void save(double t_s);

  store::Store& store_;
  std::int64_t mission_id_;
  Publish publish_;
  std::deque<store::NavRow> recent_;  // the navigation of the last few seconds
  std::vector<kinematics::SteadyLeg> legs_;
  std::vector<kinematics::SteadyLeg> motion_legs_;  // the longer steady stretches
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference_;
  std::optional<kinematics::DriftScatter> drift_scatter_;
  std::vector<std::pair<std::int64_t, kinematics::TurnSequence>> ok_turns_;
  std::optional<kinematics::CurrentEstimate> estimate_;
};

}  // namespace avk::app
