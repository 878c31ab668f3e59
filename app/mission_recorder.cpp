#include "app/mission_recorder.hpp"

#include <exception>
#include <string>
#include <utility>

namespace avk::app {

store::MissionStatus to_store_status(mission::MissionState s) {
  switch (s) {
    case mission::MissionState::running:
      return store::MissionStatus::running;
    case mission::MissionState::paused:
      return store::MissionStatus::paused;
    case mission::MissionState::interrupted:
      return store::MissionStatus::interrupted;
    case mission::MissionState::aborted:
      return store::MissionStatus::aborted;
    case mission::MissionState::halted:
      return store::MissionStatus::halted;
    case mission::MissionState::done:
      return store::MissionStatus::done;
  }
  return store::MissionStatus::interrupted;
}

MissionRecorder::MissionRecorder(store::Store& store, std::int64_t mission_id,
                                 double flush_period_s, CurrentTracker::Publish on_current)
    : store_(store),
      writer_(store),
      mission_id_(mission_id),
      flush_period_s_(flush_period_s),
      current_(store, mission_id, std::move(on_current)) {
  pending_.reserve(256);
}

MissionRecorder::~MissionRecorder() {
  // A destructor must not throw; the batch is lost only if the database itself is gone.
  try {
    flush();
  } catch (const std::exception&) {
  }
}

void MissionRecorder::on_nav(const mission::NavRecord& r) {
  pending_.push_back({r.nav.t_s, r.nav.x_m, r.nav.y_m, r.nav.heading_deg, r.nav.speed_mps,
                      r.desired_heading_deg, r.desired_speed_mps, mission::to_string(r.mode)});
  current_.nav(pending_.back());
  if (pending_.back().t_s - pending_.front().t_s >= flush_period_s_) flush();
}

void MissionRecorder::on_turn_started(const mission::TurnTask&, const mission::RunningTurn& turn) {
  current_.turn_commanded(turn.start.t_s);
}

void MissionRecorder::flush() {
  if (pending_.empty()) return;
  writer_.nav(mission_id_, pending_);
  pending_.clear();
}

void MissionRecorder::set_runner(std::optional<std::int64_t> pid) {
  writer_.runner(mission_id_, pid);
}

void MissionRecorder::on_turn(mission::TurnOutcome& t) {
  ++turns_finished_;
  t.stored_id =
      writer_.turn(mission_id_, t.raw, t.status, t.reason,
                   {t.condition_set_time_s, t.start_heading_error_deg, t.start_yaw_rate_dps});
  // A turn waiting in the spool has no id yet: the current is estimated again at the next turn
  // the database takes.
  if (t.stored_id) current_.turn_stored(*t.stored_id, t.raw, t.status);
}

void MissionRecorder::on_condition_set(const mission::ConditionSetEpisode& e) {
  writer_.condition_set(mission_id_,
                        {e.start_s, e.end_s, e.target_speed_mps, to_string(e.outcome)});
}

void MissionRecorder::on_event(const mission::MissionEventRecord& e) {
  writer_.event(mission_id_, e.t_s, std::string(mission::to_string(e.kind)), e.message);
}

void MissionRecorder::on_state(mission::MissionState s, const std::string& reason, double t_s) {
  flush();
  writer_.status(mission_id_, to_store_status(s), reason, t_s);
}

}  // namespace avk::app
