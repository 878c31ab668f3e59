#pragma once
// Turns found in a navigation log that has no turn records (an old .alog, another helm): a turn
// is a step of a held desired heading, taken from a steady course at a constant desired speed,
// recorded and judged by the same rules the mission uses (ConditionSet, TurnMonitor,
// turn_anomaly), so an extracted turn is the turn the mission would have recorded from the same
// log. Rules and their reasons: docs/alog-import.md.
//
// Fed one sample at a time, so an import never holds the log.

#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "mission/condition_set.hpp"
#include "mission/mission_config.hpp"
#include "mission/step_rejection.hpp"
#include "mission/turn_monitor.hpp"
#include "vehicle/alog.hpp"

namespace avk::mission {

struct TurnExtractorOptions {
  // Smallest step: the new desired heading minus the heading the vehicle is on (the turn's goal).
  double min_step_deg = 5.0;
  // The desired heading must have been held (within this) over the ConditionSet window before
  // the step, as the mission's ConditionSet holds its course exactly: a bearing to a point,
  // recomputed every helm tick and jittering with GNSS noise (returning, containment,
  // waypoints), is not a series of turns.
  double held_course_tolerance_deg = 0.0;
  ConditionSetConfig condition_set;
  CompletionRule completion;      // the mission's default, as the mission judges its turns
  double max_gap_s = 2.0;         // navigation gap that aborts a turn (and resets ConditionSet)
  double turn_timeout_s = 120.0;  // as the mission's turn timeout; also bounds a turn's memory
};

// A step of the desired heading that started no turn, and why (the harvester counts them).
struct SkippedStep {
  double t_s = 0.0;  // the sample before the step, where the turn would have started
  double goal_dheading_deg = 0.0;
  StepRejection reason = StepRejection::not_steady_before;
};

// How steady the vehicle was at the step that started a turn, as the ConditionSet saw it.
struct StepStart {
  double yaw_rate_dps = 0.0;     // the moving average
  double speed_error_mps = 0.0;  // speed minus the desired speed
};

class TurnExtractor {
 public:
  TurnExtractor(TurnExtractorOptions options, std::string vehicle_id, std::string mission_id);

  // Feeds the next sample (time order); returns the turn that ended with it, with
  // meta().status and meta().status_reason set: ok, rejected (turn_anomaly's reason) or aborted.
  std::optional<kinematics::TurnSequence> feed(const vehicle::GuidedNav& sample);
  // At the end of the log: the turn still being recorded, aborted.
  std::optional<kinematics::TurnSequence> finish();

  bool turning() const { return turn_.has_value(); }

  // The steps seen since the last call that started no turn, oldest first.
  std::vector<SkippedStep> take_skipped_steps() { return std::exchange(skipped_, {}); }
  // For the turn feed() or finish() returned last: why it is not ok (empty when it is), and how
  // steady its start was.
  std::optional<StepRejection> last_turn_rejection() const { return last_rejection_; }
  const StepStart& last_turn_start() const { return turn_start_; }

 private:
  kinematics::TurnSequence finish_turn(Completion how);
  kinematics::TurnSequence abort_turn(StepRejection kind, const std::string& reason);
  // Why the step at `s` starts no turn (empty: it starts one).
  std::optional<StepRejection> step_rejection(const vehicle::GuidedNav& s, double goal_deg,
                                              bool gap, bool turn_just_ended) const;
  void track_steady(const vehicle::GuidedNav& s);
  bool course_held() const;

  TurnExtractorOptions options_;
  std::string vehicle_id_;
  std::string mission_id_;
  ConditionSetMonitor steady_;
  bool steady_active_ = false;           // steady_ has a target (a desired speed is in force)
  std::deque<double> held_desired_deg_;  // desired headings of the samples steady_ was fed
  std::optional<vehicle::GuidedNav> previous_;
  std::optional<TurnMonitor> turn_;
  double turn_start_s_ = 0.0;
  double turn_desired_heading_deg_ = 0.0;
  double turn_desired_speed_mps_ = 0.0;
  StepStart turn_start_;
  std::optional<StepRejection> last_rejection_;
  std::vector<SkippedStep> skipped_;
  bool previous_was_change_ = false;  // the last sample changed the desired heading
};

}  // namespace avk::mission
