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

// Within this of the turn-back course the swing towards it is nearly over, and conditioning takes
// over holding it (a tighter test would wait out the overshoot twice).
constexpr double kTurnedBackDeg = 10.0;
// Containment ends this far past the buffer's inner edge, not on it: a boat still turning inward
// (or set by a current) would cross the edge back and forth, each crossing an interrupted
// conditioning episode.
constexpr double kLeaveContainmentM = 3.0;

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
  if (finished()) return;
  if (mode_ == HelmMode::paused) return keep_station_while_paused(now_s);

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
            cell_name(task) + ": initial yaw rate " + fixed_text(task.initial_yaw_rate_dps, 1) +
                " deg/s not reached within " +
                fixed_text(config_.turn_array.initial_yaw_rate_timeout_s, 0) + " s (last " +
                (rate ? fixed_text(*rate, 1) : std::string("none")) + " deg/s; attempt " +
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
              fixed_text(config_.condition_set.timeout_s, 0) + " s (attempt " +
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
    case HelmMode::transiting:
      // Outside the region, before the mission: to its interior at the mission's transit speed.
      desired_heading_deg_ = container_.heading_to_interior_deg({s.x_m, s.y_m});
      desired_speed_mps_ = return_speed_mps(config_);
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
  // Only the interior counts as having been inside: a mission that starts in the buffer, or
  // outside, with the vehicle drifting out in a current, transits back instead of halting.
  if (zone == RegionZone::interior) {
    been_inside_ = true;
  } else if (zone == RegionZone::outside && been_inside_) {
    // OpRegion: outside the polygon the vehicle is shut down (thesis §4.4.2).
    if (turn_) abort_turn(s.t_s, "left the operating region", false);
    stop_all(s.t_s, HelmMode::halted, MissionState::halted,
             "left the operating region at " + position_text(s));
    return;
  }
  if (!been_inside_ && zone == RegionZone::outside && mode_ == HelmMode::containing) {
    event(s.t_s, EventKind::containment,
          "outside the operating region at " + position_text(s) + ": transiting to it");
    set_mode(HelmMode::transiting, s.t_s);
  }
  switch (mode_) {
    case HelmMode::transiting:
      if (zone != RegionZone::outside) set_mode(HelmMode::containing, s.t_s);
      break;
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
        abort_turn(s.t_s, "containment: entered the buffer zone at " + position_text(s), true);
        contain(s, "entered the buffer zone during a turn");
      } else if (const Completion c = turn_->update(s); c != Completion::none) {
        finish_turn(s, c);
      } else if (s.t_s - turn_start_s_ > config_.turn_timeout_s) {
        const double goal = turn_->goal_heading_deg();
        abort_turn(
            s.t_s,
            "the turn did not complete within " + fixed_text(config_.turn_timeout_s, 0) + " s",
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
  event(s.t_s, EventKind::containment,
        why + " at " + position_text(s) + ": heading for the interior");
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
             "at the return point (" + fixed_text(d, 1) + " m away)");
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
  pause_stopped_ = true;
  if (last_nav_)
    pause_keeper_.emplace(kinematics::Point{last_nav_->x_m, last_nav_->y_m}, StationKeepConfig{});
  return true;
}

void MissionRunner::keep_station_while_paused(double now_s) {
  if (!pause_keeper_ || state_ != MissionState::paused || !last_nav_) return;
  if (vehicle_.link_state(now_s) != vehicle::LinkState::live) {
    if (!pause_stopped_) vehicle_.all_stop(now_s);
    pause_stopped_ = true;
    return;
  }
  const HelmOutput out = pause_keeper_->update(*last_nav_);
  // Idle inside the inner radius: nothing to command but the stop already given.
  if (out.speed_mps <= 0.0 && pause_stopped_) return;
  pause_stopped_ = out.speed_mps <= 0.0;
  vehicle_.command({now_s, out.heading_deg, out.speed_mps});
}

bool MissionRunner::resume(double now_s) {
  if (mode_ != HelmMode::paused || finished()) return false;
  event(now_s, EventKind::resume, "resumed");
  pause_keeper_.reset();
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
