#pragma once
// What a running mission tells the rest of the station: every navigation sample with the
// guidance in force, every turn as it ends, ConditionSet episodes, events and status changes.
// The store, the command line's progress lines and (later) the live stream each implement it.

#include <cstdint>
#include <optional>
#include <string>

#include "kinematics/turn_sequence.hpp"
#include "mission/event_kind.hpp"
#include "mission/helm_mode.hpp"
#include "mission/turn_plan.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

// Mission lifecycle, as stored (store::MissionStatus has the same names).
enum class MissionState { running, paused, interrupted, aborted, halted, done };
const char* to_string(MissionState s);
// The station status that announces a change to this state (mission_running, ...).
EventKind state_change_kind(MissionState s);

struct NavRecord {
  vehicle::NavSample nav;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  HelmMode mode = HelmMode::containing;
};

struct TurnOutcome {
  TurnTask task;
  kinematics::TurnSequence raw;  // metadata status/reason filled
  kinematics::TurnStatus status = kinematics::TurnStatus::ok;
  std::string reason;
  std::optional<double> condition_set_time_s;
  // How steady the turn began: heading minus the held course, and the moving-average yaw rate.
  std::optional<double> start_heading_error_deg;
  std::optional<double> start_yaw_rate_dps;
  std::optional<double> advance_m;  // for ok turns
  std::optional<double> transfer_m;
  bool requeued = false;                  // aborted and put back into the queue
  bool given_up = false;                  // aborted for the last allowed time
  std::optional<std::int64_t> stored_id;  // set by the observer that stores it
};

struct ConditionSetEpisode {
  double start_s = 0.0;
  double end_s = 0.0;
  double target_speed_mps = 0.0;
  enum class Outcome { set, timeout, interrupted } outcome = Outcome::set;
};
const char* to_string(ConditionSetEpisode::Outcome o);

struct MissionEventRecord {
  double t_s = 0.0;
  EventKind kind = EventKind::link;
  std::string message;
};

// The turn under way, as commanded: where and when the new heading was sent, and to which side.
// Observers take the side from here, never from a heading they saw: a 180° turn's goal is
// equally far both ways, and a page that opens mid-turn draws the turn from the same record.
struct RunningTurn {
  vehicle::NavSample start;   // the sample at which the new heading was commanded
  double speed_mps = 0.0;     // the cell's speed (u0 of a speed-change turn)
  double dheading_deg = 0.0;  // signed: + clockwise (starboard)
  double goal_heading_deg = 0.0;
  int attempt = 1;                        // 1 for the cell's first try
  std::optional<double> speed_after_mps;  // a speed-change turn's u1
};

class MissionObserver {
 public:
  virtual ~MissionObserver() = default;
  virtual void on_nav(const NavRecord&) {}
  // Observers are called in the order they were added; one that stores the turn sets stored_id,
  // so the ones after it can name the stored turn.
  virtual void on_turn_started(const TurnTask&, const RunningTurn&) {}
  virtual void on_turn(TurnOutcome&) {}
  virtual void on_condition_set(const ConditionSetEpisode&) {}
  virtual void on_event(const MissionEventRecord&) {}
  virtual void on_state(MissionState, const std::string& /*reason*/, double /*t_s*/) {}
  virtual void on_mode(HelmMode /*from*/, HelmMode /*to*/, double /*t_s*/) {}
};

}  // namespace avk::mission
