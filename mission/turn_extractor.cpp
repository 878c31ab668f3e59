#include "mission/turn_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "kinematics/angles.hpp"
#include "mission/turn_checks.hpp"

namespace avk::mission {

namespace {

// Desired headings logged as text round-trip exactly; anything below this is the same command.
constexpr double kNoChange_deg = 1e-9;

std::string num(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

bool has_guidance(const vehicle::GuidedNav& s) {
  return s.desired_heading_deg && s.desired_speed_mps;
}

}  // namespace

TurnExtractor::TurnExtractor(TurnExtractorOptions options, std::string vehicle_id,
                             std::string mission_id)
    : options_(options),
      vehicle_id_(std::move(vehicle_id)),
      mission_id_(std::move(mission_id)),
      steady_(options.condition_set, 0.0) {}

std::optional<kinematics::TurnSequence> TurnExtractor::feed(const vehicle::GuidedNav& s) {
  const bool gap = previous_ && s.nav.t_s - previous_->nav.t_s > options_.max_gap_s;
  std::optional<kinematics::TurnSequence> out;
  if (turn_) {
    if (gap) {
      out = abort_turn(StepRejection::log_gap,
                       "navigation gap of " + num(s.nav.t_s - previous_->nav.t_s, 2) + " s");
    } else if (!s.desired_heading_deg || *s.desired_heading_deg != turn_desired_heading_deg_) {
      out = abort_turn(StepRejection::goal_changed_during_turn,
                       "the desired heading changed before completion");
    } else if (!s.desired_speed_mps || *s.desired_speed_mps != turn_desired_speed_mps_) {
      out = abort_turn(StepRejection::speed_command_changed,
                       "the desired speed changed before completion");
    } else {
      const Completion c = turn_->update(s.nav);
      if (c != Completion::none) {
        out = finish_turn(c);
      } else if (s.nav.t_s - turn_start_s_ > options_.turn_timeout_s) {
        out =
            abort_turn(StepRejection::never_completed, "the turn did not complete within " +
                                                           num(options_.turn_timeout_s, 0) + " s");
      }
      // Like the mission, the next ConditionSet starts after the sample that ended the turn.
      previous_ = s;
      return out;
    }
    // An aborted turn's sample is a plain sample again: it may begin the next steady run.
  }
  if (gap) steady_active_ = false;

  // The mission starts a turn at the helm tick that finds conditions set, from the last sample;
  // the new desired heading is first in force at the sample after it. So a step seen here
  // starts at the previous sample, whose steadiness is what the monitor says now.
  const bool changed =
      previous_ && has_guidance(s) && has_guidance(*previous_) &&
      std::abs(kinematics::angle180_deg(*s.desired_heading_deg - *previous_->desired_heading_deg)) >
          kNoChange_deg;
  // A desired heading recomputed every tick (a bearing to a point) is one step, the first
  // change of its run: counting every tick would bury the real steps.
  const bool continues_run = std::exchange(previous_was_change_, changed);
  if (changed) {
    // The step is the heading change commanded from the course the vehicle is on: the turn's
    // goal, as the mission's goal heading is start heading + goal. It is not measured from the
    // old desired heading, because a vehicle in wind or current holds a steady course several
    // degrees off it: the M200 in sim-choppy.json was told to turn 10 deg by a change of 0.7 deg
    // of desired heading. Any change of a held desired heading is a new command.
    const double goal =
        kinematics::angle180_deg(*s.desired_heading_deg - previous_->nav.heading_deg);
    if (const auto why = step_rejection(s, goal, gap, out.has_value())) {
      if (!continues_run) skipped_.push_back({previous_->nav.t_s, goal, *why});
    } else {
      const auto rate = steady_.yaw_rate_dps();
      turn_start_ = {rate.value_or(0.0), previous_->nav.speed_mps - *s.desired_speed_mps};
      turn_.emplace(previous_->nav, *s.desired_speed_mps, goal, options_.completion);
      turn_start_s_ = previous_->nav.t_s;
      turn_desired_heading_deg_ = *s.desired_heading_deg;
      turn_desired_speed_mps_ = *s.desired_speed_mps;
      steady_active_ = false;
      previous_was_change_ = false;  // the desired heading is held while the turn lasts
      previous_ = s;
      if (const Completion c = turn_->update(s.nav); c != Completion::none) return finish_turn(c);
      return std::nullopt;
    }
  }
  track_steady(s);
  previous_ = s;
  return out;
}

std::optional<StepRejection> TurnExtractor::step_rejection(const vehicle::GuidedNav& s,
                                                           double goal_deg, bool gap,
                                                           bool turn_just_ended) const {
  if (gap) return StepRejection::log_gap;
  if (std::abs(goal_deg) < options_.min_step_deg) return StepRejection::too_small;
  if (*s.desired_speed_mps != *previous_->desired_speed_mps)
    return StepRejection::speed_command_changed;
  // A step on the sample that ended a turn, or before the window has filled again after a turn,
  // a gap or a new speed, starts mid-swing.
  if (turn_just_ended || !steady_active_ ||
      held_desired_deg_.size() <= static_cast<std::size_t>(options_.condition_set.window))
    return StepRejection::not_steady_before;
  if (!course_held()) return StepRejection::course_not_held;
  if (!steady_.conditions_set()) {
    return std::abs(previous_->nav.speed_mps - steady_.target_speed_mps()) >
                   options_.condition_set.speed_tolerance_mps
               ? StepRejection::speed_not_steady
               : StepRejection::not_steady_before;
  }
  return std::nullopt;
}

void TurnExtractor::track_steady(const vehicle::GuidedNav& s) {
  if (!has_guidance(s)) {
    steady_active_ = false;
    return;
  }
  // No held course for the heading test: another helm may hold a steady course several degrees
  // off its desired heading in a cross wind, and the log does not say which course it meant.
  if (!steady_active_ || *s.desired_speed_mps != steady_.target_speed_mps()) {
    steady_.reset(*s.desired_speed_mps);
    held_desired_deg_.clear();
    steady_active_ = true;
  }
  steady_.update(s.nav);
  held_desired_deg_.push_back(*s.desired_heading_deg);
  while (held_desired_deg_.size() > static_cast<std::size_t>(options_.condition_set.window) + 1)
    held_desired_deg_.pop_front();
}

bool TurnExtractor::course_held() const {
  if (held_desired_deg_.size() <= static_cast<std::size_t>(options_.condition_set.window))
    return false;
  const double last = held_desired_deg_.back();
  return std::all_of(held_desired_deg_.begin(), held_desired_deg_.end(), [&](double d) {
    return std::abs(kinematics::angle180_deg(d - last)) <= options_.held_course_tolerance_deg;
  });
}

std::optional<kinematics::TurnSequence> TurnExtractor::finish() {
  if (!turn_) return std::nullopt;
  return abort_turn(StepRejection::never_completed, "the log ended during the turn");
}

kinematics::TurnSequence TurnExtractor::finish_turn(Completion how) {
  kinematics::TurnSequence raw = turn_->build(vehicle_id_, mission_id_);
  turn_.reset();
  if (how == Completion::passed_goal)
    raw.add_warning("completed by passing the goal heading between two samples");
  const auto anomaly = find_turn_anomaly(raw, {options_.completion, options_.max_gap_s});
  raw.meta().status = anomaly ? kinematics::TurnStatus::rejected : kinematics::TurnStatus::ok;
  raw.meta().status_reason = anomaly ? anomaly->reason : "";
  last_rejection_ = anomaly ? std::optional(anomaly->kind) : std::nullopt;
  return raw;
}

kinematics::TurnSequence TurnExtractor::abort_turn(StepRejection kind, const std::string& reason) {
  kinematics::TurnSequence raw = turn_->build(vehicle_id_, mission_id_);
  last_rejection_ = kind;
  turn_.reset();
  raw.meta().status = kinematics::TurnStatus::aborted;
  raw.meta().status_reason = reason;
  return raw;
}

}  // namespace avk::mission
