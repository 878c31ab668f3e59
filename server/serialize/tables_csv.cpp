#include <algorithm>

#include "server/serialize.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

namespace {

// RFC 4180: a cell with a comma, quote or line break is quoted, its quotes doubled.
std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string optional_csv(const std::optional<double>& v) {
  return v ? num(*v) : std::string();
}

std::string mean_csv(const std::optional<kin::MeanSd>& v) {
  return v ? num(v->mean) : std::string();
}

std::string sd_csv(const std::optional<kin::MeanSd>& v) {
  return v ? num(v->sd) : std::string();
}

}  // namespace

std::string missions_csv(const std::vector<app::MissionSummary>& missions) {
  std::string csv =
      "id,vehicle_id,name,status,created_utc,started_s,ended_s,started_utc,ended_utc,turns_ok,"
      "turns_aborted,turns_rejected\n";
  for (const auto& s : missions) {
    const auto& m = s.mission;
    csv += std::to_string(m.id) + ',' + csv_cell(m.vehicle_id) + ',' + csv_cell(m.name) + ',' +
           app::to_string(s.status) + ',' + csv_cell(m.created_utc) + ',' +
           optional_csv(m.started_s) + ',' + optional_csv(m.ended_s) + ',' +
           csv_cell(m.started_utc.value_or("")) + ',' + csv_cell(m.ended_utc.value_or("")) + ',' +
           std::to_string(s.turns.ok) + ',' + std::to_string(s.turns.aborted) + ',' +
           std::to_string(s.turns.rejected) + '\n';
  }
  return csv;
}

std::string vehicles_csv(const std::vector<app::VehicleStatus>& vehicles) {
  std::string csv =
      "id,kind,max_speed_mps,link,helm_mode,desired_heading_deg,desired_speed_mps,mission_id,"
      "t_s,nav_t_s,x_m,y_m,heading_deg,speed_mps\n";
  for (const auto& v : vehicles) {
    csv += csv_cell(v.info.id) + ',' + csv_cell(v.info.kind) + ',' +
           (v.info.max_speed_mps > 0.0 ? num(v.info.max_speed_mps) : std::string()) + ',';
    if (!v.live) {
      csv += vehicle::to_string(vehicle::LinkState::disconnected);
      csv += ",,,,,,,,,,\n";
      continue;
    }
    const app::VehicleSnapshot& l = *v.live;
    csv += std::string(vehicle::to_string(l.link)) + ',' +
           (l.helm_mode ? std::string(mission::to_string(*l.helm_mode)) : std::string()) + ',' +
           optional_csv(l.desired_heading_deg) + ',' + optional_csv(l.desired_speed_mps) + ',' +
           (l.mission_id ? std::to_string(*l.mission_id) : std::string()) + ',' + num(l.t_s);
    if (l.nav)
      csv += ',' + num(l.nav->t_s) + ',' + num(l.nav->x_m) + ',' + num(l.nav->y_m) + ',' +
             num(l.nav->heading_deg) + ',' + num(l.nav->speed_mps) + '\n';
    else
      csv += ",,,,,\n";
  }
  return csv;
}

std::string events_csv(const std::vector<app::MissionEventView>& events) {
  std::string csv = "id,t_s,kind,message\n";
  for (const auto& e : events)
    csv += std::to_string(e.id) + ',' + num(e.t_s) + ',' + csv_cell(e.kind) + ',' +
           csv_cell(e.message) + '\n';
  return csv;
}

std::string nav_csv(const std::vector<app::TrackPoint>& rows) {
  std::string csv =
      "t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,helm_mode\n";
  for (const auto& r : rows) {
    const app::TrackPoint& n = r;
    csv += num(n.t_s) + ',' + num(n.x_m) + ',' + num(n.y_m) + ',' + num(n.heading_deg) + ',' +
           num(n.speed_mps) + ',' + optional_csv(n.desired_heading_deg) + ',' +
           optional_csv(n.desired_speed_mps) + ',' + csv_cell(n.helm_mode) + '\n';
  }
  return csv;
}

std::string models_csv(const std::vector<app::ModelView>& models) {
  std::string csv =
      "id,created_utc,vehicle_id,form,history_samples,rate_hz,ridge_lambda,refined,"
      "training_missions,train_one_step_rms_deg,validation_mse_m2,validation_heading_rms_deg,"
      "speed_gain,speed_sag_per_deg,speed_bias_mps\n";
  for (const auto& m : models) {
    // The training missions in one cell, space-separated: a list is not a CSV column.
    std::string missions;
    for (const auto id : m.training_missions) {
      if (!missions.empty()) missions += ' ';
      missions += std::to_string(id);
    }
    const auto& y = m.model;
    csv += std::to_string(m.id) + ',' + csv_cell(m.created_utc) + ',' + csv_cell(m.vehicle_id) +
           ',' + kin::to_string(y.form) + ',' + std::to_string(y.history) + ',' + num(y.rate_hz) +
           ',' + num(y.ridge_lambda) + ',' + (y.refined ? "true" : "false") + ',' + missions + ',' +
           optional_csv(m.train_one_step_rms_deg) + ',' + optional_csv(m.validation_mse_m2) + ',' +
           optional_csv(m.validation_heading_rms_deg) + ',' +
           (y.speed ? num(y.speed->gain) + ',' + num(y.speed->sag_per_deg) + ',' +
                          num(y.speed->bias_mps)
                    : std::string(",,")) +
           '\n';
  }
  return csv;
}

std::string report_cells_csv(const app::MissionReport& r) {
  std::string csv =
      "speed_mps,dheading_deg,planned,ok,aborted,rejected,advance_mean_m,advance_sd_m,"
      "transfer_mean_m,transfer_sd_m,condition_set_mean_s,condition_set_sd_s\n";
  for (const auto& c : r.cells)
    csv += num(c.speed_mps) + ',' + num(c.dheading_deg) + ',' + std::to_string(c.planned) + ',' +
           std::to_string(c.ok) + ',' + std::to_string(c.aborted) + ',' +
           std::to_string(c.rejected) + ',' + mean_csv(c.advance_m) + ',' + sd_csv(c.advance_m) +
           ',' + mean_csv(c.transfer_m) + ',' + sd_csv(c.transfer_m) + ',' +
           mean_csv(c.condition_set_time_s) + ',' + sd_csv(c.condition_set_time_s) + '\n';
  return csv;
}

std::string turns_csv(const std::vector<app::TurnView>& rows) {
  std::string csv =
      "id,mission_id,vehicle_id,status,reason,speed_mps,goal_dheading_deg,"
      "observed_dheading_deg,start_time_s,end_time_s,advance_m,transfer_m,"
      "condition_set_time_s,start_heading_error_deg,start_yaw_rate_dps\n";
  for (const auto& t : rows)
    csv += std::to_string(t.id) + ',' + std::to_string(t.mission_id) + ',' +
           csv_cell(t.vehicle_id) + ',' + kin::to_string(t.status) + ',' + csv_cell(t.reason) +
           ',' + num(t.commanded_speed_mps) + ',' + num(t.goal_dheading_deg) + ',' +
           num(t.observed_dheading_deg) + ',' + num(t.start_time_s) + ',' + num(t.end_time_s) +
           ',' + optional_csv(t.advance_m) + ',' + optional_csv(t.transfer_m) + ',' +
           optional_csv(t.condition_set_time_s) + ',' + optional_csv(t.start_heading_error_deg) +
           ',' + optional_csv(t.start_yaw_rate_dps) + '\n';
  return csv;
}

std::string trajectory_csv(const kin::Polyline& line) {
  std::string csv = "vertex_index,x_m,y_m\n";
  for (std::size_t i = 0; i < line.size(); ++i)
    csv += std::to_string(i) + ',' + num(line[i].x_m) + ',' + num(line[i].y_m) + '\n';
  return csv;
}

std::string sweep_csv(const std::vector<kin::HistorySweepRow>& rows) {
  std::string csv =
      "history_s,history_samples,train_one_step_rms_deg,validation_mse_m2,"
      "validation_heading_rms_deg,validation_turns\n";
  for (const auto& r : rows)
    csv += num(r.history_s) + ',' + std::to_string(r.history) + ',' +
           num(r.train_one_step_rms_deg) + ',' + num(r.validation.position_mse_m2) + ',' +
           num(r.validation.heading_rms_deg) + ',' + std::to_string(r.validation.windows) + '\n';
  return csv;
}

std::string predictive_csv(const app::Comparison& c) {
  std::string out =
      "speed_mps,dheading_deg,n_turns,span_m,avk_path_m,avk_path_sd_m,model_path_m,"
      "model_path_sd_m,instantaneous_path_m,instantaneous_path_sd_m,avk_yx_mse_m2,"
      "model_yx_mse_m2,instantaneous_yx_mse_m2,corridor_inside,corridor_total\n";
  const auto path = [](const kin::HeldOutScores* s) {
    if (!s) return std::string(",");
    const kin::MeanSd m = s->path();
    return num(m.mean) + ',' + num(m.sd);
  };
  const auto mse = [](const kin::HeldOutScores* s) {
    return s ? num(s->yx_mse().mean) : std::string();
  };
  for (const auto& cell : c.predictive) {
    const kin::HeldOutScores* m = cell.model ? &*cell.model : nullptr;
    out += num(cell.speed_mps) + ',' + num(cell.dheading_deg) + ',' + std::to_string(cell.n_turns) +
           ',' + num(cell.span_m) + ',' + path(&cell.avk) + ',' + path(m) + ',' +
           path(&cell.instantaneous) + ',' + mse(&cell.avk) + ',' + mse(m) + ',' +
           mse(&cell.instantaneous) + ',' +
           (cell.coverage ? std::to_string(cell.coverage->inside) : std::string()) + ',' +
           (cell.coverage ? std::to_string(cell.coverage->total) : std::string()) + '\n';
  }
  return out;
}

std::string comparison_csv(const app::Comparison& c) {
  const auto mse = [](const kin::MethodError* e) { return e ? num(e->mse_m2) : std::string(); };
  const auto pct = [](const kin::MethodError* e) {
    return e && e->improvement_pct ? num(*e->improvement_pct) : std::string();
  };
  const auto advance = [](const kin::MethodError* e) {
    return e ? num(e->advance_error_m) : std::string();
  };
  const auto transfer = [](const kin::MethodError* e) {
    return e ? num(e->transfer_error_m) : std::string();
  };
  std::string out =
      "speed_mps,dheading_deg,n_turns,outliers,avk_mse_m2,model_mse_m2,"
      "instantaneous_mse_m2,avk_improvement_pct,model_improvement_pct,"
      "avk_advance_error_m,model_advance_error_m,instantaneous_advance_error_m,"
      "avk_transfer_error_m,model_transfer_error_m,instantaneous_transfer_error_m\n";
  for (const auto& cell : c.cells) {
    const kin::MethodError* m = cell.model ? &*cell.model : nullptr;
    const kin::MethodError* a = &cell.avk;
    const kin::MethodError* i = &cell.instantaneous;
    out += num(cell.speed_mps) + ',' + num(cell.dheading_deg) + ',' + std::to_string(cell.n_turns) +
           ',' + std::to_string(std::count(cell.outlier.begin(), cell.outlier.end(), true)) + ',' +
           mse(a) + ',' + mse(m) + ',' + mse(i) + ',' + pct(a) + ',' + pct(m) + ',' + advance(a) +
           ',' + advance(m) + ',' + advance(i) + ',' + transfer(a) + ',' + transfer(m) + ',' +
           transfer(i) + '\n';
  }
  return out;
}

}  // namespace avk::server
