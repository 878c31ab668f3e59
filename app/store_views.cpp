#include "app/store_views.hpp"

namespace avk::app {

namespace {

// A model goes both ways (stored when fitted, read when listed) with the same fields.
template <class To, class From>
To same_model(const From& m) {
  return {.id = m.id,
          .created_utc = m.created_utc,
          .vehicle_id = m.vehicle_id,
          .training_missions = m.training_missions,
          .model = m.model,
          .train_one_step_rms_deg = m.train_one_step_rms_deg,
          .validation_mse_m2 = m.validation_mse_m2,
          .validation_heading_rms_deg = m.validation_heading_rms_deg};
}

}  // namespace

MissionStatus view_of(store::MissionStatus s) {
  switch (s) {
    case store::MissionStatus::created:
      return MissionStatus::created;
    case store::MissionStatus::running:
      return MissionStatus::running;
    case store::MissionStatus::paused:
      return MissionStatus::paused;
    case store::MissionStatus::interrupted:
      return MissionStatus::interrupted;
    case store::MissionStatus::aborted:
      return MissionStatus::aborted;
    case store::MissionStatus::halted:
      return MissionStatus::halted;
    case store::MissionStatus::done:
      return MissionStatus::done;
  }
  return MissionStatus::interrupted;
}

store::MissionStatus to_store(MissionStatus s) {
  switch (s) {
    case MissionStatus::created:
      return store::MissionStatus::created;
    case MissionStatus::running:
      return store::MissionStatus::running;
    case MissionStatus::paused:
      return store::MissionStatus::paused;
    case MissionStatus::interrupted:
      return store::MissionStatus::interrupted;
    case MissionStatus::aborted:
      return store::MissionStatus::aborted;
    case MissionStatus::halted:
      return store::MissionStatus::halted;
    case MissionStatus::done:
      return store::MissionStatus::done;
  }
  return store::MissionStatus::interrupted;
}

// The API shows the names the store keeps: both are fixed, so they are one list.
const char* to_string(MissionStatus s) {
  return store::to_string(to_store(s));
}

MissionView view_of(const store::Mission& m) {
  return {.id = m.id,
          .vehicle_id = m.vehicle_id,
          .name = m.name,
          .config_json = m.config_json,
          .status = view_of(m.status),
          .status_reason = m.status_reason,
          .created_utc = m.created_utc,
          .started_s = m.started_s,
          .ended_s = m.ended_s,
          .started_utc = m.started_utc,
          .ended_utc = m.ended_utc};
}

TurnCounts view_of(const store::TurnCounts& c) {
  return {.ok = c.ok, .aborted = c.aborted, .rejected = c.rejected};
}

MissionEventView view_of(const store::MissionEvent& e) {
  return {
      .id = e.id, .mission_id = e.mission_id, .t_s = e.t_s, .kind = e.kind, .message = e.message};
}

TrackPoint view_of(const store::NavPageRow& r) {
  const store::NavRow& n = r.row;
  return {.rowid = r.rowid,
          .t_s = n.t_s,
          .x_m = n.x_m,
          .y_m = n.y_m,
          .heading_deg = n.heading_deg,
          .speed_mps = n.speed_mps,
          .desired_heading_deg = n.desired_heading_deg,
          .desired_speed_mps = n.desired_speed_mps,
          .helm_mode = n.helm_mode};
}

TurnView view_of(const store::TurnRow& t) {
  return {.id = t.id,
          .mission_id = t.mission_id,
          .vehicle_id = t.vehicle_id,
          .cell_speed_mps = t.cell_speed_mps,
          .cell_dheading_deg = t.cell_dheading_deg,
          .status = t.status,
          .reason = t.reason,
          .commanded_speed_mps = t.commanded_speed_mps,
          .goal_dheading_deg = t.goal_dheading_deg,
          .observed_dheading_deg = t.observed_dheading_deg,
          .start_time_s = t.start_time_s,
          .end_time_s = t.end_time_s,
          .advance_m = t.advance_m,
          .transfer_m = t.transfer_m,
          .condition_set_time_s = t.condition_set_time_s,
          .start_heading_error_deg = t.start_heading_error_deg,
          .start_yaw_rate_dps = t.start_yaw_rate_dps,
          .source = t.source,
          .quality = t.quality,
          .speed_after_mps = t.speed_after_mps};
}

TurnDetail view_of(store::StoredTurn t) {
  return {.row = view_of(t.row), .raw = std::move(t.raw), .normalized = std::move(t.normalized)};
}

CurrentView view_of(const store::StoredCurrent& c) {
  return {.mission_id = c.mission_id,
          .t_s = c.t_s,
          .method = c.method,
          .estimate = c.estimate,
          .revision = c.revision,
          .speed_reference = c.speed_reference,
          .drift_scatter = c.drift_scatter};
}

ModelView view_of(const store::StoredModel& m) {
  return same_model<ModelView>(m);
}

std::vector<vehicle::GuidedNav> guided_log(const std::vector<store::NavRow>& rows) {
  std::vector<vehicle::GuidedNav> out;
  out.reserve(rows.size());
  for (const auto& r : rows) {
    vehicle::GuidedNav g;
    g.nav.t_s = r.t_s;
    g.nav.x_m = r.x_m;
    g.nav.y_m = r.y_m;
    g.nav.heading_deg = r.heading_deg;
    g.nav.speed_mps = r.speed_mps;
    g.desired_heading_deg = r.desired_heading_deg;
    g.desired_speed_mps = r.desired_speed_mps;
    out.push_back(std::move(g));
  }
  return out;
}

store::TurnFilter to_store(const TurnQuery& q) {
  return {.mission_id = q.mission_id,
          .speed_mps = q.speed_mps,
          .dheading_deg = q.dheading_deg,
          .status = q.status,
          .speed_tolerance_mps = q.speed_tolerance_mps,
          .dheading_tolerance_deg = q.dheading_tolerance_deg,
          .after_id = q.after_id,
          .limit = q.limit};
}

store::StoredModel to_store(const ModelView& m) {
  return same_model<store::StoredModel>(m);
}

}  // namespace avk::app
