#include "mission/mission_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "kinematics/angles.hpp"
#include "kinematics/turn_measures.hpp"
#include "mission/turn_checks.hpp"

namespace avk::mission {

namespace {

using kinematics::TurnSide;
using kinematics::TurnStatus;

// Fixed decimals for messages an operator reads.
std::string num(double v, int decimals = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Within this of the turn-back course the swing towards it is nearly over, and conditioning takes
// over holding it (a tighter test would wait out the overshoot twice).
constexpr double kTurnedBackDeg = 10.0;
// Containment ends this far past the buffer's inner edge, not on it: a boat still turning inward
// (or set by a current) would cross the edge back and forth, each crossing an interrupted
// conditioning episode.
constexpr double kLeaveContainmentM = 3.0;

std::string cell_name(const TurnTask& t) {
  std::string out = num(t.speed_mps, 2);
  if (t.speed_after_mps) {
    out += " -> ";
    out += num(*t.speed_after_mps, 2);
  }
  out += " m/s, ";
  out += num(t.dheading_deg, 0);
  out += " deg";
  return out;
}

std::string at(const vehicle::NavSample& s) {
  std::string out = "(";
  out += num(s.x_m, 1);
  out += ", ";
  out += num(s.y_m, 1);
  out += ") m";
  return out;
}

// The event that logs a mission stopping short in this state. Reaching done is the ordinary end,
// and a pause has logged its own event already.
std::optional<EventKind> stop_event_kind(MissionState s) {
  switch (s) {
    case MissionState::halted:
      return EventKind::halted;
    case MissionState::aborted:
      return EventKind::aborted;
    case MissionState::interrupted:
      return EventKind::interrupted;
    case MissionState::running:
    case MissionState::paused:
    case MissionState::done:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

const char* to_string(MissionState s) {
  switch (s) {
    case MissionState::running:
      return "running";
    case MissionState::paused:
      return "paused";
    case MissionState::interrupted:
      return "interrupted";
    case MissionState::aborted:
      return "aborted";
    case MissionState::halted:
      return "halted";
    case MissionState::done:
      return "done";
  }
  return "?";
}

EventKind state_change_kind(MissionState s) {
  switch (s) {
    case MissionState::running:
      return EventKind::mission_running;
    case MissionState::paused:
      return EventKind::mission_paused;
    case MissionState::interrupted:
      return EventKind::mission_interrupted;
    case MissionState::aborted:
      return EventKind::mission_aborted;
    case MissionState::halted:
      return EventKind::mission_halted;
    case MissionState::done:
      return EventKind::mission_done;
  }
  return EventKind::mission_running;
}

const char* to_string(ConditionSetEpisode::Outcome o) {
  switch (o) {
    case ConditionSetEpisode::Outcome::set:
      return "set";
    case ConditionSetEpisode::Outcome::timeout:
      return "timeout";
    case ConditionSetEpisode::Outcome::interrupted:
      return "interrupted";
  }
  return "?";
}

MissionRunner::MissionRunner(MissionConfig config, vehicle::Vehicle& vehicle,
                             std::vector<TurnTask> tasks, RunnerOptions options)
    : config_(std::move(config)),
      vehicle_(vehicle),
      options_(std::move(options)),
      container_(config_.region),
      queue_(tasks.begin(), tasks.end()),
      rng_(config_.excitation ? config_.excitation->seed : 1) {
  for (const TurnTask& t : plan_turns(config_)) {
    if (!cell_of(t))
      cells_.push_back({t.speed_mps, t.dheading_deg, 0, 0, 0, 0, 0, false, t.speed_after_mps});
    ++cell_of(t)->planned;
  }
  for (CellProgress& c : cells_) {
    const auto left = std::count_if(queue_.begin(), queue_.end(), [&](const TurnTask& t) {
      return same_cell(t.speed_mps, t.speed_after_mps, t.dheading_deg, c.speed_mps,
                       c.speed_after_mps, c.dheading_deg);
    });
    c.ok = c.planned - static_cast<int>(left);
  }
}

CellProgress* MissionRunner::cell_of(const TurnTask& t) {
  for (CellProgress& c : cells_)
    if (same_cell(t.speed_mps, t.speed_after_mps, t.dheading_deg, c.speed_mps, c.speed_after_mps,
                  c.dheading_deg))
      return &c;
  return nullptr;
}

bool MissionRunner::finished() const {
  return state_ && (*state_ == MissionState::done || *state_ == MissionState::halted ||
                    *state_ == MissionState::aborted || *state_ == MissionState::interrupted);
}

void MissionRunner::set_mode(HelmMode m, double t_s) {
  if (m == mode_) return;
  const HelmMode from = mode_;
  mode_ = m;
  for (auto* o : observers_)
    o->on_mode(from, m, t_s);
}

void MissionRunner::set_state(MissionState s, const std::string& reason, double t_s) {
  state_ = s;
  for (auto* o : observers_)
    o->on_state(s, reason, t_s);
}

void MissionRunner::event(double t_s, EventKind kind, const std::string& message) {
  const MissionEventRecord e{t_s, kind, message};
  for (auto* o : observers_)
    o->on_event(e);
}

void MissionRunner::tick(double now_s) {
  if (!state_) set_state(MissionState::running, "", now_s);
  for (const vehicle::NavSample& s : vehicle_.take_nav())
    process(s);
  if (finished() || mode_ == HelmMode::paused) return;

  const bool live = vehicle_.link_state(now_s) == vehicle::LinkState::live;
  if (!live && last_nav_ && !holding_) {
    // Without navigation nothing can be recorded or contained: stop and wait.
    holding_ = true;
    if (turn_) abort_turn(now_s, "navigation lost during the turn", true);
    if (condition_set_) end_condition_set(now_s, ConditionSetEpisode::Outcome::interrupted);
    vehicle_.all_stop(now_s);
    event(now_s, EventKind::link,
          std::string("navigation ") + vehicle::to_string(vehicle_.link_state(now_s)) +
              ": all stop until it is back");
    if (mode_ != HelmMode::returning && mode_ != HelmMode::exciting)
      set_mode(HelmMode::containing, now_s);
  } else if (live && holding_) {
    holding_ = false;
    event(now_s, EventKind::link, "navigation is back");
  }
  if (holding_ || !last_nav_) return;

  // The helm acts on the latest navigation, as pHelmIvP does at its AppTick.
  if (mode_ == HelmMode::conditioning && !pre_turn_side_ && condition_set_->conditions_set()) {
    if (queue_.front().initial_yaw_rate_dps != 0.0) {
      start_pre_turn(*last_nav_);
    } else {
      start_turn(*last_nav_);
    }
  }
  if (mode_ == HelmMode::conditioning && pre_turn_side_) {
    if (pre_turn_in_band()) {
      start_turn(*last_nav_);
    } else if (last_nav_->t_s - pre_turn_start_s_ > config_.turn_array.initial_yaw_rate_timeout_s) {
      const std::optional<double> rate = condition_set_->yaw_rate_dps();
      end_condition_set(last_nav_->t_s, ConditionSetEpisode::Outcome::timeout);
      TurnTask& task = queue_.front();
      ++task.attempts;
      event(now_s, EventKind::condition_set_timeout,
            cell_name(task) + ": initial yaw rate " + num(task.initial_yaw_rate_dps, 1) +
                " deg/s not reached within " +
                num(config_.turn_array.initial_yaw_rate_timeout_s, 0) + " s (last " +
                (rate ? num(*rate, 1) : std::string("none")) + " deg/s; attempt " +
                std::to_string(task.attempts) + ")");
      TurnOutcome no_turn;  // the turn was never commanded: nothing was recorded
      give_up_or_requeue(now_s, no_turn);
      start_conditioning(*last_nav_);
    }
  }
  if (mode_ == HelmMode::conditioning && !pre_turn_side_ &&
      last_nav_->t_s - condition_set_start_s_ > config_.condition_set.timeout_s) {
    end_condition_set(last_nav_->t_s, ConditionSetEpisode::Outcome::timeout);
    TurnTask& task = queue_.front();
    ++task.attempts;
    event(now_s, EventKind::condition_set_timeout,
          "conditions for " + cell_name(task) + " not set within " +
              num(config_.condition_set.timeout_s, 0) + " s (attempt " +
              std::to_string(task.attempts) + ")");
    TurnOutcome no_turn;  // conditions never set: nothing was recorded
    give_up_or_requeue(now_s, no_turn);
    start_conditioning(*last_nav_, held_course_deg_);
  }
  if (config_.kind == MissionKind::persistent_excitation && excite_start_s_ &&
      (mode_ == HelmMode::exciting || mode_ == HelmMode::containing) &&
      now_s - *excite_start_s_ >= config_.excitation->duration_s) {
    start_returning(now_s);
  }
  if (mode_ == HelmMode::exciting && now_s >= next_step_s_) {
    const auto& e = *config_.excitation;
    const double step =
        std::uniform_real_distribution<double>(e.min_step_deg, e.max_step_deg)(rng_);
    const double sign = std::bernoulli_distribution(0.5)(rng_) ? 1.0 : -1.0;
    desired_heading_deg_ =
        kinematics::wrap360_deg(desired_heading_deg_.value_or(0.0) + sign * step);
    next_step_s_ =
        now_s + std::uniform_real_distribution<double>(e.min_interval_s, e.max_interval_s)(rng_);
  }
  if (finished()) return;
  update_desired(now_s);
  if (commands_motion(mode_) && desired_heading_deg_ && desired_speed_mps_)
    vehicle_.command({now_s, *desired_heading_deg_, *desired_speed_mps_});
}

void MissionRunner::update_desired(double) {
  const auto& s = *last_nav_;
  switch (mode_) {
    case HelmMode::containing:
      desired_heading_deg_ = turn_back_course_deg_
                                 ? *turn_back_course_deg_
                                 : container_.heading_to_interior_deg({s.x_m, s.y_m});
      if (!queue_.empty()) {
        desired_speed_mps_ = queue_.front().speed_mps;
      } else if (config_.excitation) {
        desired_speed_mps_ = config_.excitation->speed_mps;
      } else {
        desired_speed_mps_ = return_speed_mps(config_);
      }
      break;
    case HelmMode::returning: {
      const auto& rp = config_.region.return_point;
      desired_heading_deg_ = kinematics::heading_of_deg(rp.x_m - s.x_m, rp.y_m - s.y_m);
      desired_speed_mps_ = return_speed_mps(config_);
      break;
    }
    default:
      break;  // conditioning, turning and exciting hold what they set
  }
}

void MissionRunner::process(const vehicle::NavSample& s) {
  for (auto* o : observers_)
    o->on_nav({s, desired_heading_deg_, desired_speed_mps_, mode_});
  last_nav_ = s;
  if (finished() || mode_ == HelmMode::paused || holding_) return;
  const RegionZone zone = container_.zone({s.x_m, s.y_m});
  if (zone != RegionZone::outside) {
    been_inside_ = true;
  } else if (been_inside_) {
    // OpRegion: outside the polygon the vehicle is shut down (thesis §4.4.2).
    if (turn_) abort_turn(s.t_s, "left the operating region", false);
    stop_all(s.t_s, HelmMode::halted, MissionState::halted,
             "left the operating region at " + at(s));
    return;
  }
  switch (mode_) {
    case HelmMode::containing:
      if (zone == RegionZone::buffer) {
        turn_back_course_deg_.reset();  // in the buffer the container steers, as always
      } else if (zone == RegionZone::interior && turn_back_course_deg_) {
        // Turned back early: conditions start once the heading is near the new course.
        if (std::abs(kinematics::angle180_deg(s.heading_deg - *turn_back_course_deg_)) <=
            kTurnedBackDeg)
          start_conditioning(s, *turn_back_course_deg_, false);
      } else if (zone == RegionZone::interior &&
                 container_.depth_in_interior_m({s.x_m, s.y_m}) >= kLeaveContainmentM) {
        leave_containment(s);
      }
      break;
    case HelmMode::conditioning:
      if (zone == RegionZone::buffer) {
        contain(s, "entered the buffer zone while setting conditions");
      } else {
        condition_set_->update(s);
      }
      break;
    case HelmMode::turning:
      if (zone == RegionZone::buffer) {
        abort_turn(s.t_s, "containment: entered the buffer zone at " + at(s), true);
        contain(s, "entered the buffer zone during a turn");
      } else if (const Completion c = turn_->update(s); c != Completion::none) {
        finish_turn(s, c);
      } else if (s.t_s - turn_start_s_ > config_.turn_timeout_s) {
        const double goal = turn_->goal_heading_deg();
        abort_turn(s.t_s,
                   "the turn did not complete within " + num(config_.turn_timeout_s, 0) + " s",
                   true);
        start_conditioning(s, goal);
      }
      break;
    case HelmMode::exciting:
      if (zone == RegionZone::buffer) contain(s, "entered the buffer zone");
      break;
    case HelmMode::returning:
      check_return(s);
      break;
    default:
      break;
  }
}

void MissionRunner::contain(const vehicle::NavSample& s, const std::string& why) {
  turn_back_course_deg_.reset();
  if (condition_set_) end_condition_set(s.t_s, ConditionSetEpisode::Outcome::interrupted);
  event(s.t_s, EventKind::containment, why + " at " + at(s) + ": heading for the interior");
  set_mode(HelmMode::containing, s.t_s);
}

void MissionRunner::leave_containment(const vehicle::NavSample& s) {
  if (config_.kind == MissionKind::persistent_excitation) {
    start_exciting(s, s.t_s);
  } else {
    // The course the container was steering, not the heading of the moment: the boat is still
    // swinging towards it.
    start_conditioning(s, desired_heading_deg_);
  }
}

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
          "less than " + num(needed_m, 0) + " m ahead on " + num(course, 0) +
              " deg before the buffer at " + at(s) + ": turning to " + num(back, 0) + " deg first");
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
          "persistent excitation for " + num(config_.excitation->duration_s, 0) + " s at " +
              num(config_.excitation->speed_mps) + " m/s");
  }
  desired_heading_deg_ = s.heading_deg;
  desired_speed_mps_ = config_.excitation->speed_mps;
  next_step_s_ = now_s;
  set_mode(HelmMode::exciting, now_s);
}

void MissionRunner::start_returning(double t_s) {
  if (condition_set_) end_condition_set(t_s, ConditionSetEpisode::Outcome::interrupted);
  return_best_m_ = std::numeric_limits<double>::infinity();
  event(t_s, EventKind::returning, "heading for the return point");
  set_mode(HelmMode::returning, t_s);
}

void MissionRunner::check_return(const vehicle::NavSample& s) {
  const double d = kinematics::distance_m({s.x_m, s.y_m}, config_.region.return_point);
  const double capture = config_.region.capture_radius_m;
  // Like a MOOS waypoint's slip radius: close enough and moving away counts as arrived, so a
  // vehicle whose turning circle is wider than the capture radius does not orbit the point.
  // A margin of up to 2 m keeps GNSS noise (decimetres) from looking like moving away.
  const bool slipped = d <= 3.0 * capture && d > return_best_m_ + std::min(2.0, capture);
  return_best_m_ = std::min(return_best_m_, d);
  if (d <= capture || slipped) {
    stop_all(s.t_s, HelmMode::done, MissionState::done,
             "at the return point (" + num(d, 1) + " m away)");
  }
}

void MissionRunner::stop_all(double t_s, HelmMode mode, MissionState state,
                             const std::string& reason) {
  if (condition_set_) end_condition_set(t_s, ConditionSetEpisode::Outcome::interrupted);
  vehicle_.all_stop(t_s);
  desired_heading_deg_.reset();
  desired_speed_mps_.reset();
  set_mode(mode, t_s);
  if (const auto kind = stop_event_kind(state)) event(t_s, *kind, reason);
  set_state(state, reason, t_s);
}

bool MissionRunner::pause(double now_s, const std::string& reason) {
  if (finished() || mode_ == HelmMode::paused) return false;
  if (turn_) abort_turn(now_s, reason, false);
  paused_from_ = mode_;
  event(now_s, EventKind::pause, reason);
  stop_all(now_s, HelmMode::paused, MissionState::paused, reason);
  return true;
}

bool MissionRunner::resume(double now_s) {
  if (mode_ != HelmMode::paused || finished()) return false;
  event(now_s, EventKind::resume, "resumed");
  set_state(MissionState::running, "", now_s);
  turn_back_course_deg_.reset();
  if (paused_from_ == HelmMode::returning) {
    start_returning(now_s);
  } else {
    // Containment re-enters conditioning (or excitation) as soon as the vehicle is inside.
    set_mode(HelmMode::containing, now_s);
  }
  return true;
}

bool MissionRunner::abort(double now_s, const std::string& reason) {
  if (finished()) return false;
  if (turn_) abort_turn(now_s, reason, false);
  stop_all(now_s, HelmMode::halted, MissionState::aborted, reason);
  return true;
}

void MissionRunner::interrupt(double now_s, const std::string& reason) {
  if (finished()) return;
  if (turn_) abort_turn(now_s, reason, false);
  stop_all(now_s, HelmMode::paused, MissionState::interrupted, reason);
}

}  // namespace avk::mission
