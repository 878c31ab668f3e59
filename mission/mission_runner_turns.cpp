#include "mission/mission_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "kinematics/angles.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/turn_measures.hpp"
#include "mission/runner_text.hpp"
#include "mission/turn_checks.hpp"

namespace avk::mission {

namespace {

using kinematics::TurnSide;
using kinematics::TurnStatus;

using kinematics::fixed_text;

}  // namespace

void MissionRunner::start_conditioning(const vehicle::NavSample& s,
                                       std::optional<double> course_deg, bool may_turn_back) {
  if (queue_.empty()) {
    start_returning(s.t_s);
    return;
  }
  // ConditionSet notes a course on becoming active and holds it (thesis §4.4.1). After a turn
  // that is the turn's goal, where the boat is still swinging to: the heading at completion is
  // up to the completion threshold short of it.
  const double course = kinematics::wrap360_deg(course_deg.value_or(s.heading_deg));
  const double speed = queue_.front().speed_mps;
  const double needed_m = speed * config_.condition_set.run_ahead_s + kConditioningTurnRoomM;
  const kinematics::Point here{s.x_m, s.y_m};
  const double run_m = may_turn_back && config_.condition_set.run_ahead_s > 0.0
                           ? container_.run_before_buffer_m(here, course, needed_m)
                           : needed_m;
  // Inward as the container steers: a course along a boundary leaves no room for a drift.
  const double back = container_.heading_to_interior_deg(here);
  // Turning back must buy room: where no course has more, conditions are set where the boat is.
  if (run_m < needed_m &&
      container_.run_before_buffer_m(here, back, needed_m) > run_m + kConditioningTurnRoomM) {
    turn_back_course_deg_ = back;
    desired_heading_deg_ = back;
    desired_speed_mps_ = speed;
    event(s.t_s, EventKind::turning_back,
          "less than " + fixed_text(needed_m, 0) + " m ahead on " + fixed_text(course, 0) +
              " deg before the buffer at " + position_text(s) + ": turning to " +
              fixed_text(back, 0) + " deg first");
    set_mode(HelmMode::containing, s.t_s);
    return;
  }
  turn_back_course_deg_.reset();
  held_course_deg_ = course;
  condition_set_.emplace(config_.condition_set, speed, held_course_deg_);
  condition_set_start_s_ = s.t_s;
  desired_heading_deg_ = held_course_deg_;
  desired_speed_mps_ = queue_.front().speed_mps;
  set_mode(HelmMode::conditioning, s.t_s);
}

void MissionRunner::end_condition_set(double t_s, ConditionSetEpisode::Outcome outcome) {
  const ConditionSetEpisode e{condition_set_start_s_, t_s, condition_set_->target_speed_mps(),
                              outcome};
  condition_set_.reset();
  pre_turn_side_.reset();
  for (auto* o : observers_)
    o->on_condition_set(e);
}

const kinematics::Ckt* MissionRunner::table_for_auto() {
  if (!ok_turns_.empty() && own_table_turns_ != ok_turns_.size()) {
    own_table_ = kinematics::Ckt::build(ok_turns_);
    own_table_turns_ = ok_turns_.size();
  }
  const double u = queue_.front().speed_mps;
  const kinematics::Ckt* own = own_table_ ? &*own_table_ : nullptr;
  for (const kinematics::Ckt* t : {own, options_.prior_table}) {
    if (!t) continue;
    const auto range = t->speed_range_mps();
    if (range && u >= range->first && u <= range->second) return t;
  }
  return nullptr;
}

TurnSide MissionRunner::side_for(const TurnTask& task, const vehicle::NavSample& s) {
  if (task.side) return *task.side;
  const SideChoice c =
      choose_side(container_, {s.x_m, s.y_m, s.heading_deg}, task.speed_mps, task.dheading_deg,
                  table_for_auto(), next_auto_preference_, options_.direction);
  next_auto_preference_ = c.side == TurnSide::right ? TurnSide::left : TurnSide::right;
  return c.side;
}

void MissionRunner::start_pre_turn(const vehicle::NavSample& s) {
  const TurnTask& task = queue_.front();
  pre_turn_side_ = side_for(task, s);
  pre_turn_start_s_ = s.t_s;
  // Into the coming turn: the pre-turn turns to the turn's side; against it: to the other side.
  const double turn_sign = *pre_turn_side_ == TurnSide::right ? 1.0 : -1.0;
  const double sign = task.initial_yaw_rate_dps > 0.0 ? turn_sign : -turn_sign;
  desired_heading_deg_ =
      kinematics::wrap360_deg(s.heading_deg + sign * config_.turn_array.pre_turn_dheading_deg);
}

bool MissionRunner::pre_turn_in_band() const {
  const std::optional<double> rate = condition_set_->yaw_rate_dps();
  if (!rate) return false;
  const double into_turn = *pre_turn_side_ == TurnSide::right ? *rate : -*rate;
  return std::abs(into_turn - queue_.front().initial_yaw_rate_dps) <=
         config_.turn_array.initial_yaw_rate_band_dps;
}

void MissionRunner::start_turn(const vehicle::NavSample& s) {
  const double cs_time = s.t_s - condition_set_start_s_;
  turn_start_heading_error_deg_ = condition_set_->heading_error_deg();
  turn_start_yaw_rate_dps_ = condition_set_->yaw_rate_dps();
  TurnTask& task = queue_.front();
  const TurnSide side = pre_turn_side_ ? *pre_turn_side_ : side_for(task, s);
  end_condition_set(s.t_s, ConditionSetEpisode::Outcome::set);
  const double signed_dheading = side == TurnSide::left ? -task.dheading_deg : task.dheading_deg;
  turn_.emplace(s, task.speed_mps, signed_dheading, config_.completion);
  running_turn_ = RunningTurn{s,
                              task.speed_mps,
                              signed_dheading,
                              turn_->goal_heading_deg(),
                              task.attempts + 1,
                              task.speed_after_mps};
  turn_start_s_ = s.t_s;
  turn_condition_set_time_s_ = cs_time;
  desired_heading_deg_ = turn_->goal_heading_deg();
  // A speed-change turn sends the new heading with the new speed.
  desired_speed_mps_ = task.speed_after_mps.value_or(task.speed_mps);
  if (auto* c = cell_of(task)) c->running = true;
  set_mode(HelmMode::turning, s.t_s);
  for (auto* o : observers_)
    o->on_turn_started(task, *running_turn_);
}

void MissionRunner::finish_turn(const vehicle::NavSample& s, Completion how) {
  const double goal_deg = turn_->goal_heading_deg();
  TurnOutcome out;
  out.task = queue_.front();
  out.raw = turn_->build(options_.vehicle_id, options_.mission_label);
  out.raw.meta().speed_after_mps = out.task.speed_after_mps;
  if (how == Completion::passed_goal)
    out.raw.add_warning("completed by passing the goal heading between two samples");
  out.condition_set_time_s = turn_condition_set_time_s_;
  out.start_heading_error_deg = turn_start_heading_error_deg_;
  out.start_yaw_rate_dps = turn_start_yaw_rate_dps_;
  out.raw.meta().initial_yaw_rate_dps = turn_start_yaw_rate_dps_;
  turn_.reset();
  running_turn_.reset();
  const auto anomaly = turn_anomaly(out.raw, {config_.completion, options_.max_sample_gap_s});
  CellProgress* cell = cell_of(out.task);
  if (cell) cell->running = false;
  if (anomaly) {
    out.status = TurnStatus::rejected;
    out.reason = *anomaly;
    TurnTask& task = queue_.front();
    ++task.attempts;
    out.task = task;
    if (cell) ++cell->rejected;
    give_up_or_requeue(s.t_s, out);
    event(s.t_s, EventKind::turn_rejected, cell_name(out.task) + ": " + *anomaly);
  } else {
    const auto at = kinematics::advance_transfer(out.raw.normalized().points());
    out.advance_m = at.advance_m;
    out.transfer_m = at.transfer_m;
    ok_turns_.push_back(out.raw);
    if (cell) ++cell->ok;
    queue_.pop_front();
  }
  out.raw.meta().status = out.status;
  out.raw.meta().status_reason = out.reason;
  for (auto* o : observers_)
    o->on_turn(out);
  // The next ConditionSet holds the goal this turn was commanded to.
  start_conditioning(s, goal_deg);
}

void MissionRunner::give_up_or_requeue(double t_s, TurnOutcome& out) {
  const TurnTask& task = queue_.front();
  if (task.attempts < config_.turn_array.max_attempts) {
    out.requeued = true;
    return;
  }
  out.given_up = true;
  ++given_up_;
  if (auto* c = cell_of(task)) ++c->given_up;
  event(t_s, EventKind::turn_given_up,
        cell_name(task) + " given up after " + std::to_string(task.attempts) + " attempts");
  queue_.pop_front();
}

void MissionRunner::abort_turn(double t_s, const std::string& reason, bool count_attempt) {
  TurnOutcome out;
  TurnTask& task = queue_.front();
  if (count_attempt) ++task.attempts;
  out.task = task;
  out.raw = turn_->build(options_.vehicle_id, options_.mission_label);
  out.raw.meta().speed_after_mps = task.speed_after_mps;
  out.status = TurnStatus::aborted;
  out.reason = reason;
  out.raw.meta().status = out.status;
  out.raw.meta().status_reason = reason;
  out.condition_set_time_s = turn_condition_set_time_s_;
  out.start_heading_error_deg = turn_start_heading_error_deg_;
  out.start_yaw_rate_dps = turn_start_yaw_rate_dps_;
  out.raw.meta().initial_yaw_rate_dps = turn_start_yaw_rate_dps_;
  turn_.reset();
  running_turn_.reset();
  CellProgress* cell = cell_of(task);
  if (cell) {
    cell->running = false;
    ++cell->aborted;
  }
  give_up_or_requeue(t_s, out);
  event(t_s, EventKind::turn_aborted,
        cell_name(out.task) + ": " + reason +
            (out.requeued ? "; re-queued"
                          : "; given up after " + std::to_string(out.task.attempts) + " attempts"));
  for (auto* o : observers_)
    o->on_turn(out);
}

void MissionRunner::start_exciting(const vehicle::NavSample& s, double now_s) {
  if (!excite_start_s_) {
    excite_start_s_ = now_s;
    event(now_s, EventKind::excitation,
          "persistent excitation for " + fixed_text(config_.excitation->duration_s, 0) + " s at " +
              fixed_text(config_.excitation->speed_mps, 2) + " m/s");
  }
  desired_heading_deg_ = s.heading_deg;
  desired_speed_mps_ = config_.excitation->speed_mps;
  next_step_s_ = now_s;
  set_mode(HelmMode::exciting, now_s);
}

}  // namespace avk::mission
