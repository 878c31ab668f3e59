#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "kinematics/angles.hpp"
#include "kinematics/ckt3_file.hpp"
#include "kinematics/colregs.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/position_band.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/yaw_model_json.hpp"
#include "server/serialize.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

std::string num(double v) {
  return kin::number_text(v);
}

std::string fixed(double v, int decimals) {
  return kin::fixed_text(v, decimals);
}

std::optional<std::int64_t> record_id(const std::string& text) {
  std::size_t used = 0;
  long long id = 0;
  try {
    id = std::stoll(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || used != text.size() || id <= 0) return std::nullopt;
  return static_cast<std::int64_t>(id);
}

json optional_json(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

json optional_json(const std::optional<std::int64_t>& v) {
  return v ? json(*v) : json();
}

json mean_sd_json(const std::optional<kin::MeanSd>& v) {
  return v ? json{{"mean", v->mean}, {"sd", v->sd}} : json();
}

json points_json(const kin::Polyline& line) {
  json a = json::array();
  for (const auto& p : line)
    a.push_back({p.x_m, p.y_m});
  return a;
}

std::string describe_value(const json& v) {
  // Dumping a container whole would grow the message with the input, and recurse as deep as it
  // nests.
  if (v.is_structured()) return std::string("an ") + v.type_name();
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  constexpr std::size_t kMax = 40;
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

// --- vehicles ------------------------------------------------------------------------------

json frontseat_json(const vehicle::M200Status& s) {
  const auto& c = s.counters;
  return {{"connected", s.connected},
          {"failsafe", vehicle::to_string(s.failsafe)},
          {"battery_v", s.battery ? json(s.battery->stack_v) : json()},
          {"sentences", c.sentences},
          {"bad_lines", c.errors},
          {"last_error", c.last_error},
          {"pydir_sent", c.pydir_sent},
          {"failsafe_stops", c.failsafe_stops},
          {"disconnects", c.disconnects},
          {"last_link_error", s.last_link_error}};
}

namespace {

json helm_mode_json(const std::optional<mission::HelmMode>& m) {
  return m ? json(mission::to_string(*m)) : json();
}

}  // namespace

json vehicle_json(const app::VehicleStatus& v) {
  json j = {{"id", v.info.id},
            {"kind", v.info.kind.empty() ? json() : json(v.info.kind)},
            {"max_speed_mps", v.info.max_speed_mps > 0.0 ? json(v.info.max_speed_mps) : json()}};
  if (!v.live) {
    j["link"] = vehicle::to_string(vehicle::LinkState::disconnected);
    j["nav"] = nullptr;
    return j;
  }
  const app::VehicleSnapshot& s = *v.live;
  j["link"] = vehicle::to_string(s.link);
  j["helm_mode"] = helm_mode_json(s.helm_mode);
  j["desired_heading_deg"] = optional_json(s.desired_heading_deg);
  j["desired_speed_mps"] = optional_json(s.desired_speed_mps);
  j["mission_id"] = optional_json(s.mission_id);
  j["t_s"] = s.t_s;
  j["nav"] = s.nav ? json{{"t_s", s.nav->t_s},
                          {"x_m", s.nav->x_m},
                          {"y_m", s.nav->y_m},
                          {"heading_deg", s.nav->heading_deg},
                          {"speed_mps", s.nav->speed_mps}}
                   : json();
  // A real vehicle's link health: what an operator checks before trusting the turns.
  if (s.frontseat) j["frontseat"] = frontseat_json(*s.frontseat);
  return j;
}

json nav_topic_json(const app::VehicleSnapshot& s) {
  json j = {{"vehicle_id", s.info.id}, {"link", vehicle::to_string(s.link)}};
  if (s.nav) {
    j["t_s"] = s.nav->t_s;
    j["x_m"] = s.nav->x_m;
    j["y_m"] = s.nav->y_m;
    j["heading_deg"] = s.nav->heading_deg;
    j["speed_mps"] = s.nav->speed_mps;
  }
  // A real vehicle's battery and link health ride along with its navigation, so an operator
  // sees a sagging pack or a noisy link live.
  if (s.frontseat) j["frontseat"] = frontseat_json(*s.frontseat);
  return j;
}

json helm_topic_json(const app::VehicleSnapshot& s) {
  return {{"vehicle_id", s.info.id},
          {"mode", helm_mode_json(s.helm_mode)},
          {"desired_heading_deg", optional_json(s.desired_heading_deg)},
          {"desired_speed_mps", optional_json(s.desired_speed_mps)},
          {"mission_id", optional_json(s.mission_id)}};
}

// --- missions ------------------------------------------------------------------------------

json mission_json(const app::MissionSummary& s) {
  const store::Mission& m = s.mission;
  return {{"id", m.id},
          {"vehicle_id", m.vehicle_id},
          {"name", m.name},
          {"status", store::to_string(s.status)},
          {"status_reason", m.status_reason},
          {"created_utc", m.created_utc},
          {"started_s", optional_json(m.started_s)},
          {"ended_s", optional_json(m.ended_s)},
          {"started_utc", m.started_utc ? json(*m.started_utc) : json()},
          {"ended_utc", m.ended_utc ? json(*m.ended_utc) : json()},
          {"turns",
           {{"ok", s.turns.ok}, {"aborted", s.turns.aborted}, {"rejected", s.turns.rejected}}}};
}

json cells_json(const std::vector<app::CellReport>& cells) {
  json out = json::array();
  for (const auto& c : cells) {
    out.push_back({{"speed_mps", c.speed_mps},
                   {"dheading_deg", c.dheading_deg},
                   {"planned", c.planned},
                   {"ok", c.ok},
                   {"aborted", c.aborted},
                   {"rejected", c.rejected},
                   {"given_up", c.given_up},
                   {"running", c.running},
                   {"advance_m", mean_sd_json(c.advance_m)},
                   {"transfer_m", mean_sd_json(c.transfer_m)},
                   {"condition_set_time_s", mean_sd_json(c.condition_set_time_s)}});
    if (c.speed_after_mps) out.back()["speed_after_mps"] = *c.speed_after_mps;
  }
  return out;
}

json running_turn_json(const mission::RunningTurn& t) {
  return {{"t_s", t.start.t_s},
          {"x_m", t.start.x_m},
          {"y_m", t.start.y_m},
          {"heading_deg", t.start.heading_deg},
          {"speed_mps", t.speed_mps},
          {"dheading_deg", t.dheading_deg},
          {"goal_heading_deg", t.goal_heading_deg},
          {"attempt", t.attempt},
          {"speed_after_mps", optional_json(t.speed_after_mps)}};
}

json report_json(const app::MissionReport& r, bool with_config) {
  json j = mission_json(r.summary);
  j["status"] = app::status_text(r);
  j["live"] = r.live;
  j["helm_mode"] = helm_mode_json(r.helm_mode);
  j["running_turn"] = r.running_turn ? running_turn_json(*r.running_turn) : json();
  if (with_config) j["config"] = json::parse(r.summary.mission.config_json, nullptr, false);
  j["cells"] = cells_json(r.cells);
  j["duration_s"] = optional_json(r.duration_s);
  j["condition_set_time_s"] = mean_sd_json(r.condition_set_time_s);
  j["condition_set"] = {{"episodes", r.condition_set_episodes},
                        {"time_to_set_s", mean_sd_json(r.condition_set_time_s)},
                        {"turn_starts", r.condition_set_count}};
  j["turn_list"] = json::array();
  for (const auto& t : r.turns)
    j["turn_list"].push_back(turn_row_json(t));
  return j;
}

json event_json(const store::MissionEvent& e) {
  return {{"id", e.id}, {"t_s", e.t_s}, {"kind", e.kind}, {"message", e.message}};
}

json nav_row_json(const store::NavRow& n) {
  return {{"t_s", n.t_s},
          {"x_m", n.x_m},
          {"y_m", n.y_m},
          {"heading_deg", n.heading_deg},
          {"speed_mps", n.speed_mps},
          {"desired_heading_deg", optional_json(n.desired_heading_deg)},
          {"desired_speed_mps", optional_json(n.desired_speed_mps)},
          {"helm_mode", n.helm_mode}};
}

// --- turns ---------------------------------------------------------------------------------

json turn_row_json(const store::TurnRow& t) {
  return {{"id", t.id},
          {"mission_id", t.mission_id},
          {"vehicle_id", t.vehicle_id},
          {"status", kin::to_string(t.status)},
          {"reason", t.reason},
          {"speed_mps", t.commanded_speed_mps},
          {"goal_dheading_deg", t.goal_dheading_deg},
          {"observed_dheading_deg", t.observed_dheading_deg},
          {"start_time_s", t.start_time_s},
          {"end_time_s", t.end_time_s},
          {"advance_m", optional_json(t.advance_m)},
          {"transfer_m", optional_json(t.transfer_m)},
          {"condition_set_time_s", optional_json(t.condition_set_time_s)},
          {"start_heading_error_deg", optional_json(t.start_heading_error_deg)},
          {"start_yaw_rate_dps", optional_json(t.start_yaw_rate_dps)},
          {"source", kin::to_string(t.source)},
          {"quality", optional_json(t.quality)},
          {"speed_after_mps", optional_json(t.speed_after_mps)}};
}

json harvest_report_json(const app::HarvestReport& r) {
  return {{"mission_id", r.mission_id},
          {"vehicle_id", r.vehicle_id},
          {"harvest_id", r.harvest_id},
          {"nav_rows", r.nav_rows},
          {"steps", r.steps},
          {"harvested", r.harvested},
          {"already_recorded", r.already_recorded},
          {"rejected", r.rejected},
          {"rejected_by_reason", r.rejected_by_reason},
          {"turn_ids", r.turn_ids},
          {"mean_quality", r.harvested > 0 ? json(r.mean_quality) : json()}};
}

json turn_json(const store::StoredTurn& t) {
  json j = turn_row_json(t.row);
  j["raw"] = json::parse(kin::to_json_string(t.raw));
  j["normalized"] = t.normalized ? json::parse(kin::to_json_string(*t.normalized)) : json();
  return j;
}

// --- the CKT, predictions ------------------------------------------------------------------

namespace {

json cell_summary_json(const kin::CktCell& c) {
  return {{"speed_mps", c.speed_mps},
          {"dheading_deg", c.dheading_deg},
          {"n_turns", c.n_turns},
          {"advance_m", mean_sd_json(c.advance_m)},
          {"transfer_m", mean_sd_json(c.transfer_m)},
          {"avk_error_m2", optional_json(c.avk_error_m2)}};
}

// The current an answer applied, with its source, and the 1-sigma uncertainty of the estimate
// it came from: of each component, and of its speed and direction when there is a current.
json answer_current_json(const std::optional<kin::WaterCurrent>& current,
                         const std::optional<std::string>& source,
                         const std::optional<std::array<double, 3>>& covariance) {
  json c = water_current_json(current, source);
  if (c.is_null() && source) c = {{"source", *source}};
  if (covariance && c.is_object()) {
    c["covariance_m2ps2"] = *covariance;
    c["east_sd_mps"] = std::sqrt(std::max(0.0, (*covariance)[0]));
    c["north_sd_mps"] = std::sqrt(std::max(0.0, (*covariance)[2]));
    if (current) {
      kin::CurrentEstimate e;
      e.east_mps = current->east_mps;
      e.north_mps = current->north_mps;
      e.covariance = *covariance;
      c["speed_sd_mps"] = e.speed_sd_mps();
      c["toward_sd_deg"] = e.toward_sd_deg();
    }
  }
  return c;
}

json speed_reference_json(const app::AnswerMotion& motion) {
  return {{"value", motion.speed_over_ground ? "over_ground" : "through_water"},
          {"source", motion.speed_reference_source}};
}

}  // namespace

json ckt_summary_json(const app::VehicleTable& t) {
  json cells = json::array();
  for (const auto& c : t.table->cells())
    cells.push_back(cell_summary_json(c));
  const auto range = t.table->speed_range_mps();
  return {{"vehicle_id", t.vehicle_id},
          {"source", app::to_string(t.source)},
          {"include", t.include_harvested ? "harvested" : "collection"},
          {"snapshot_id", optional_json(t.snapshot_id)},
          {"speeds_mps", t.table->grid().speeds_mps},
          {"dheadings_deg", t.table->grid().dheadings_deg},
          {"speed_range_mps", range ? json{range->first, range->second} : json()},
          {"cells", cells}};
}

json ckt_cell_json(const app::SidedCell& s) {
  const kin::CktCell& c = s.cell;
  json j = cell_summary_json(c);
  j["dheading_deg"] = s.dheading_deg;
  j["side"] = s.side == kin::TurnSide::left ? "port" : "starboard";
  json turns = json::array();
  for (std::size_t i = 0; i < c.turns.size() && i < s.turns.size(); ++i)
    turns.push_back({{"mission_id", c.turns[i].meta().mission_id},
                     {"initial_heading_deg", c.turns[i].meta().initial_heading_deg},
                     {"points", points_json(s.turns[i])}});
  j["turns"] = std::move(turns);
  j["mean"] = points_json(s.mean_turn);
  j["trajectory"] = points_json(s.trajectory);
  j["fit"] = s.fit ? points_json(*s.fit) : json();
  return j;
}

json prediction_json(const app::Prediction& p) {
  const app::PredictQuery& q = p.query;
  json j = {{"method", app::to_string(q.method)},
            {"vehicle_id", q.vehicle_id},
            {"speed_mps", q.speed_mps},
            {"dheading_deg", q.dheading_deg},
            {"frame", q.pose ? "world" : "normalized"}};
  if (q.method == app::PredictionMethod::avk) {
    j["advance_m"] = optional_json(p.advance_m);
    j["transfer_m"] = optional_json(p.transfer_m);
    j["exact_cell"] = p.exact_cell ? json(*p.exact_cell) : json();
    j["extrapolated"] = p.extrapolated ? json(*p.extrapolated) : json();
    j["table_source"] = p.table_source ? json(*p.table_source) : json();
    j["snapshot_id"] = optional_json(p.snapshot_id);
    j["short_of_goal"] = p.short_of_goal;
    if (q.initial_yaw_rate_dps) {
      j["cell_source"] = p.cell_source ? json(*p.cell_source) : json();
      j["yaw_rate_clamped"] = p.yaw_rate_clamped ? json(*p.yaw_rate_clamped) : json();
    }
    if (p.corridor) {
      const auto& c = *p.corridor;
      j["corridor"] = {{"share", c.share},
                       {"n_turns", c.n_turns},
                       {"s_m", c.s_m},
                       {"half_width_m", c.half_width_m},
                       {"left", points_json(c.left)},
                       {"right", points_json(c.right)}};
    } else {
      j["corridor"] = nullptr;
    }
  }
  if (q.method == app::PredictionMethod::model) {
    j["model_id"] = optional_json(p.model_id);
    j["speed_model"] = q.use_speed_model;
  }
  if (p.table_frame) j["table_frame"] = *p.table_frame;
  // "frame" says where the trajectory is placed (world or normalised); "relative_to" what it
  // moves against: the ground, where the station knows the current, else the water.
  j["relative_to"] = p.frame;
  j["current"] = answer_current_json(p.current, p.current_source, p.current_covariance);
  j["speed_reference"] = speed_reference_json(p.motion);
  if (q.initial_yaw_rate_dps) j["initial_yaw_rate_dps"] = *q.initial_yaw_rate_dps;
  if (q.without_mission_id) j["without_mission_id"] = *q.without_mission_id;
  if (q.without_turn_id) j["without_turn_id"] = *q.without_turn_id;
  if (q.speed_after_mps) {
    j["speed_after_mps"] = *q.speed_after_mps;
    j["speed_change_source"] =
        p.speed_change_source ? json(app::to_string(*p.speed_change_source)) : json();
    j["speed_response"] = p.speed_response ? json(*p.speed_response) : json();
  }
  j["trajectory"] = points_json(p.trajectory);
  return j;
}

json water_current_json(const std::optional<kin::WaterCurrent>& c,
                        const std::optional<std::string>& source) {
  if (!c) return nullptr;
  return {{"east_mps", c->east_mps},
          {"north_mps", c->north_mps},
          {"speed_mps", std::hypot(c->east_mps, c->north_mps)},
          {"toward_deg", kin::heading_of_deg(c->east_mps, c->north_mps)},
          {"source", source ? json(*source) : json()}};
}

json current_estimate_json(const kin::CurrentEstimate& e) {
  return {
      {"east_mps", e.east_mps},
      {"north_mps", e.north_mps},
      {"speed_mps", e.speed_mps()},
      {"toward_deg", e.toward_deg()},
      {"speed_sd_mps", e.speed_sd_mps()},
      {"toward_sd_deg", e.toward_sd_deg()},
      {"covariance", {{"ee", e.covariance[0]}, {"en", e.covariance[1]}, {"nn", e.covariance[2]}}},
      {"residual_rms_mps", e.residual_rms_mps},
      {"speed_scale", e.speed_scale},
      {"evidence", e.legs}};
}

json mission_current_json(const app::MissionCurrent& c,
                          const std::optional<store::StoredCurrent>& stored) {
  const auto& e = c.result.estimate;
  return {{"mission_id", c.mission_id},
          {"turns", c.turns},
          {"legs_used", c.legs_used},
          {"estimate", e ? current_estimate_json(*e) : json()},
          {"significant", e ? json(app::current_is_significant(*e)) : json()},
          {"why_not", e ? json() : json(c.result.why_not)},
          {"stored", stored ? current_estimate_json(stored->estimate) : json()},
          {"stored_revision", stored ? json(stored->revision) : json()},
          {"motion_legs", c.motion_legs},
          {"speed_reference", speed_reference_evidence_json(c.speed_reference)},
          {"drift_scatter", drift_scatter_json(c.drift_scatter)}};
}

json current_json(const std::string& vehicle_id, const store::StoredCurrent& c) {
  json j = current_estimate_json(c.estimate);
  j["vehicle_id"] = vehicle_id;
  j["estimated"] = true;
  j["mission_id"] = c.mission_id;
  j["t_s"] = c.t_s;
  j["method"] = c.method;
  j["revision"] = c.revision;
  j["significant"] = app::current_is_significant(c.estimate);
  j["speed_reference"] = speed_reference_evidence_json(c.speed_reference);
  j["drift_scatter"] = drift_scatter_json(c.drift_scatter);
  return j;
}

json speed_reference_evidence_json(const std::optional<kin::SpeedReferenceEvidence>& e) {
  if (!e) return nullptr;
  return {{"legs", e->legs},
          {"rms_over_ground_mps", e->rms_over_ground_mps},
          {"rms_through_water_mps", e->rms_through_water_mps},
          {"separation_mps", e->separation_mps},
          {"identified", e->identified ? json(kin::to_string(*e->identified)) : json()}};
}

json drift_scatter_json(const std::optional<kin::DriftScatter>& d) {
  if (!d) return nullptr;
  return {{"along_mps", d->along_mps},
          {"cross_mps", d->cross_mps},
          {"legs", d->legs},
          {"mean_leg_s", d->mean_leg_s}};
}

json vehicle_motion_json(const app::VehicleMotion& m) {
  const app::MotionSpeedReference& r = m.speed_reference;
  const auto& e = r.evidence;
  json reference = {{"value", kin::to_string(r.value)},
                    {"source", r.source},
                    {"mission_id", optional_json(r.mission_id)},
                    {"rms_over_ground_mps", e ? json(e->rms_over_ground_mps) : json()},
                    {"rms_through_water_mps", e ? json(e->rms_through_water_mps) : json()},
                    {"separation_mps", e ? json(e->separation_mps) : json()},
                    {"legs", e ? json(e->legs) : json()},
                    {"missions",
                     {{"over_ground", r.missions_over_ground},
                      {"through_water", r.missions_through_water},
                      {"undetermined", r.missions_undetermined}}}};
  json scatter = drift_scatter_json(m.drift_scatter.scatter);
  scatter["source"] = m.drift_scatter.source;
  scatter["missions"] = m.drift_scatter.missions;
  json current = nullptr;
  if (m.current) {
    current = current_estimate_json(m.current->estimate);
    current["mission_id"] = m.current->mission_id;
    current["t_s"] = m.current->t_s;
    current["revision"] = m.current->revision;
  }
  return {{"vehicle_id", m.vehicle_id},
          {"speed_reference", reference},
          {"drift_scatter", scatter},
          {"current", current}};
}

json yaw_rate_table_json(const app::YawRateTable& t) {
  json coverage = json::array();
  for (const auto& c : t.coverage) {
    coverage.push_back({{"initial_yaw_rate_dps", c.initial_yaw_rate_dps},
                        {"measured", c.measured},
                        {"model", c.model},
                        {"empty", c.empty}});
  }
  json checks = json::array();
  for (const auto& c : t.model_checks) {
    checks.push_back({{"speed_mps", c.speed_mps},
                      {"dheading_deg", c.dheading_deg},
                      {"initial_yaw_rate_dps", c.initial_yaw_rate_dps},
                      {"n_turns", c.n_turns},
                      {"model_path_m", c.model_error_m},
                      {"table_path_m", c.table_error_m}});
  }
  return {{"model_id", optional_json(t.model_id)},
          {"coverage", std::move(coverage)},
          {"model_checks", std::move(checks)},
          {"ckt", kin::yaw_rate_ckt_to_json(t.table)}};
}

// --- maneuvers ------------------------------------------------------------------------------

std::vector<std::size_t> thinned_indices(const kin::TimedPath& path, double step_s) {
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const bool last = i + 1 == path.size();
    if (keep.empty() || last || !(step_s > 0.0) || path[i].t_s - path[keep.back()].t_s >= step_s)
      keep.push_back(i);
  }
  return keep;
}

namespace {

json timed_points_json(const kin::TimedPath& path, const std::vector<std::size_t>& keep) {
  json a = json::array();
  for (const std::size_t i : keep)
    a.push_back({path[i].t_s, path[i].x_m, path[i].y_m});
  return a;
}

json point_json(const kin::Point& p) {
  return {{"x_m", p.x_m}, {"y_m", p.y_m}};
}

json optional_approach_json(const std::optional<kin::Approach>& a) {
  return a ? approach_json(*a) : json();
}

// The position band at the kept points: the ellipse of the share about each point.
json band_json(const std::vector<kin::Covariance2>& cov, const std::vector<std::size_t>& keep,
               double share) {
  json out = json::array();
  for (const std::size_t i : keep) {
    if (i >= cov.size()) break;
    const kin::BandEllipse e = kin::band_ellipse(cov[i], share);
    out.push_back(
        {{"major_m", e.major_m}, {"minor_m", e.minor_m}, {"major_axis_deg", e.major_axis_deg}});
  }
  return out;
}

json candidate_json(const kin::CandidateEvaluation& c, double path_step_s, double share) {
  const std::vector<std::size_t> keep = thinned_indices(c.path, path_step_s);
  json widths = json::array();
  if (c.half_width_m.size() == c.path.size())
    for (const std::size_t i : keep)
      widths.push_back(c.half_width_m[i]);
  json contacts = json::array();
  for (const auto& a : c.contacts)
    contacts.push_back({{"cpa", approach_json(a.cpa)},
                        {"edge_cpa", optional_approach_json(a.edge_cpa)},
                        {"risk", a.risk}});
  return {{"dheading_deg", c.dheading_deg},
          {"speed_mps", c.speed_mps},
          {"path", timed_points_json(c.path, keep)},
          {"half_width_m", c.half_width_m.empty() ? json() : widths},
          {"band", band_json(c.covariance_m2, keep, share)},
          {"contacts", std::move(contacts)},
          {"min_cpa_m", c.min_cpa_m},
          {"min_edge_cpa_m", optional_json(c.min_edge_cpa_m)},
          {"clears", c.clears},
          {"risk", c.risk}};
}

// What an answer's paths are relative to: the frame, the current and its uncertainty, and what
// it assumed of the vehicle's speed loop and scatter.
void put_answer_frame(json& j, const std::string& frame,
                      const std::optional<kin::WaterCurrent>& current,
                      const std::optional<std::string>& source,
                      const std::optional<std::array<double, 3>>& covariance,
                      const app::AnswerMotion& motion) {
  j["frame"] = frame;
  j["current"] = answer_current_json(current, source, covariance);
  j["speed_reference"] = speed_reference_json(motion);
  j["scatter"] = {{"along_mps", motion.scatter.along_mps},
                  {"cross_mps", motion.scatter.cross_mps},
                  {"source", motion.scatter_source}};
}

}  // namespace

json timed_path_json(const kin::TimedPath& path, double step_s) {
  return timed_points_json(path, thinned_indices(path, step_s));
}

json approach_json(const kin::Approach& a) {
  return {{"distance_m", a.distance_m}, {"time_s", a.time_s}};
}

json contact_json(const kin::Contact& c) {
  return {{"x_m", c.x_m}, {"y_m", c.y_m}, {"course_deg", c.course_deg}, {"speed_mps", c.speed_mps}};
}

namespace {

// The evaluation's document; its candidates array left empty unless with_candidates.
json evaluation_document(const app::ManeuverEvaluation& e, double path_step_s,
                         bool with_candidates) {
  const app::ManeuverQuery& q = e.query;
  json contacts = json::array();
  for (const auto& c : q.contacts)
    contacts.push_back(contact_json(c));
  json candidates = json::array();
  if (with_candidates)
    for (const auto& c : e.candidates)
      candidates.push_back(candidate_json(c, path_step_s, q.corridor_share));
  json chosen;
  if (e.chosen) {
    const kin::CandidateEvaluation& c = e.candidates.at(*e.chosen);
    json situations = json::array();
    for (const auto s : e.choice.situations)
      situations.push_back(kin::to_string(s));
    chosen = {
        {"index", *e.chosen},
        {"dheading_deg", c.dheading_deg},
        {"min_cpa_m", c.min_cpa_m},
        {"min_edge_cpa_m", optional_json(c.min_edge_cpa_m)},
        {"risk", c.risk},
        {"margin_m", e.choice.margin_m},
        {"within_limit", e.choice.within_limit},
        {"colregs_rule", e.choice.colregs_rule.empty() ? json() : json(e.choice.colregs_rule)},
        {"situations", std::move(situations)},
        {"explanation", e.choice.explanation}};
  }
  json out = {{"vehicle_id", q.vehicle_id},
              {"method", app::to_string(q.method)},
              {"model_id", optional_json(e.model_id)},
              {"table_source", e.table_source ? json(*e.table_source) : json()},
              {"timed_by_turns", e.timed_by_turns},
              {"own",
               {{"x_m", q.own.x_m},
                {"y_m", q.own.y_m},
                {"heading_deg", q.own.heading_deg},
                {"speed_mps", q.speed_mps}}},
              {"contacts", std::move(contacts)},
              {"standoff_m", q.standoff_m},
              {"horizon_s", q.horizon_s},
              {"corridor", q.corridor_share},
              {"use_corridor", q.use_corridor},
              {"path_step_s", path_step_s},
              {"rule", q.corridor_rule ? "corridor" : "risk"},
              {"max_risk", q.max_risk},
              {"prefer_starboard", q.prefer_starboard},
              {"band_share", q.corridor_share},
              {"candidates", std::move(candidates)},
              {"chosen", std::move(chosen)}};
  put_answer_frame(out, e.frame, e.current, e.current_source, e.current_covariance, e.motion);
  return out;
}

}  // namespace

json maneuver_evaluation_json(const app::ManeuverEvaluation& e, double path_step_s) {
  return evaluation_document(e, path_step_s, true);
}

std::string maneuver_evaluation_text(const app::ManeuverEvaluation& e, double path_step_s) {
  // The document with an empty candidates array, dumped, then the candidates written into it.
  // A compact dump is the concatenation of its parts' dumps, so this is the whole document's.
  // The key cannot be matched inside a string value: there its quotes are escaped.
  const std::string head = evaluation_document(e, path_step_s, false).dump();
  static constexpr std::string_view kEmpty = R"("candidates":[])";
  const auto at = head.find(kEmpty);
  if (at == std::string::npos)
    throw std::logic_error("maneuver evaluation: no candidates array in the document");
  const auto split = at + kEmpty.size() - 1;  // before the closing bracket
  std::string out(head, 0, split);
  for (std::size_t i = 0; i < e.candidates.size(); ++i) {
    if (i) out += ',';
    out += candidate_json(e.candidates[i], path_step_s, e.query.corridor_share).dump();
  }
  out.append(head, split, std::string::npos);
  return out;
}

json ongoing_maneuver_json(const app::OngoingManeuver& o) {
  const app::OngoingQuery& q = o.query;
  const kin::OngoingEvaluation& e = o.evaluation;
  json band_now;
  if (e.band_ellipse) {
    band_now = {{"major_m", e.band_ellipse->major_m},
                {"minor_m", e.band_ellipse->minor_m},
                {"major_axis_deg", e.band_ellipse->major_axis_deg}};
    if (e.inside_band) band_now["inside"] = *e.inside_band;
  }
  json out = {
      {"vehicle_id", q.vehicle_id},
      {"method", app::to_string(q.method)},
      {"model_id", optional_json(o.model_id)},
      {"start", {{"x_m", q.start.x_m}, {"y_m", q.start.y_m}, {"heading_deg", q.start.heading_deg}}},
      {"dheading_deg", q.dheading_deg},
      {"speed_mps", q.speed_mps},
      {"elapsed_s", e.elapsed_s},
      {"corridor", q.corridor_share},
      {"expected", point_json(e.expected)},
      {"measured", q.measured ? point_json(*q.measured) : json()},
      {"half_width_m", optional_json(e.half_width_m)},
      {"deviation_m", optional_json(e.deviation_m)},
      {"cross_track_m", optional_json(e.cross_track_m)},
      {"inside_corridor", e.inside_corridor ? json(*e.inside_corridor) : json()},
      {"band_now", std::move(band_now)},
      {"remaining", timed_path_json(e.remaining)},
      {"prediction", timed_path_json(o.prediction)}};
  put_answer_frame(out, o.frame, o.current, o.current_source, o.current_covariance, o.motion);
  return out;
}

json simulated_maneuver_json(const app::SimulatedManeuver& s, kin::Point origin,
                             std::optional<double> standoff_m, double path_step_s) {
  kin::TimedPath track = s.track;
  for (auto& p : track) {
    p.x_m += origin.x_m;
    p.y_m += origin.y_m;
  }
  json cpa = json::array();
  for (const auto& a : s.cpa)
    cpa.push_back(approach_json(a));
  return {{"track", timed_path_json(track, path_step_s)},
          {"cpa", std::move(cpa)},
          {"min_cpa_m", s.min_cpa_m},
          {"standoff_m", optional_json(standoff_m)},
          {"violated", standoff_m ? json(s.min_cpa_m < *standoff_m) : json()}};
}

// --- models, the comparison ----------------------------------------------------------------

json model_json(const store::StoredModel& m, bool with_coefficients) {
  json j = json::parse(kin::yaw_model_to_json(m.model));
  j["id"] = m.id;
  j["created_utc"] = m.created_utc;
  j["vehicle_id"] = m.vehicle_id;
  j["training_missions"] = m.training_missions;
  j["train_one_step_rms_deg"] = optional_json(m.train_one_step_rms_deg);
  j["validation_mse_m2"] = optional_json(m.validation_mse_m2);
  j["validation_heading_rms_deg"] = optional_json(m.validation_heading_rms_deg);
  if (!with_coefficients) {
    j.erase("error_coeffs");
    j.erase("heading_coeffs");
  }
  return j;
}

json model_headings_json(const app::ModelHeadings& h) {
  const auto optional_array = [](const std::vector<std::optional<double>>& v) {
    json a = json::array();
    for (const auto& x : v)
      a.push_back(optional_json(x));
    return a;
  };
  json segments = json::array();
  for (const auto& s : h.segments)
    segments.push_back({{"t0_s", s.t0_s},
                        {"heading_deg", s.heading_deg},
                        {"desired_heading_deg", s.desired_heading_deg},
                        {"one_step_deg", optional_array(s.one_step_deg)},
                        {"simulated_deg", optional_array(s.simulated_deg)}});
  return {{"model_id", h.model_id},
          {"mission_id", h.mission_id},
          {"dt_s", h.dt_s},
          {"warmup_samples", h.warmup},
          {"restart_step_deg", h.restart_step_deg},
          {"segments", segments}};
}

json sweep_json(const std::vector<kin::HistorySweepRow>& rows) {
  json out = json::array();
  for (const auto& row : rows)
    out.push_back({{"history_s", row.history_s},
                   {"history_samples", row.history},
                   {"train_one_step_rms_deg", row.train_one_step_rms_deg},
                   {"validation_mse_m2", row.validation.position_mse_m2},
                   {"validation_heading_rms_deg", row.validation.heading_rms_deg},
                   {"validation_turns", row.validation.windows}});
  return out;
}

namespace {

json error_json(const kin::MethodError& e) {
  return {{"mse_m2", e.mse_m2},
          {"improvement_pct", optional_json(e.improvement_pct)},
          {"advance_error_m", e.advance_error_m},
          {"transfer_error_m", e.transfer_error_m}};
}

json optional_error_json(const std::optional<kin::MethodError>& e) {
  return e ? error_json(*e) : json();
}

}  // namespace

json held_out_json(const kin::HeldOutScores* s) {
  if (!s) return json();
  const kin::MeanSd path = s->path(), mse = s->yx_mse();
  return {{"path_m", {{"mean", path.mean}, {"sd", path.sd}}},
          {"yx_mse_m2", {{"mean", mse.mean}, {"sd", mse.sd}}}};
}

json coverage_json(const kin::Coverage& c) {
  return {{"inside", c.inside}, {"total", c.total}, {"share", c.total ? json(c.share()) : json()}};
}

json predictive_json(const app::Comparison& c) {
  json cells = json::array();
  std::size_t below_70 = 0;
  for (const auto& cell : c.predictive) {
    json j = {{"speed_mps", cell.speed_mps},
              {"dheading_deg", cell.dheading_deg},
              {"n_turns", cell.n_turns},
              {"span_m", cell.span_m},
              {"avk", held_out_json(&cell.avk)},
              {"model", held_out_json(cell.model ? &*cell.model : nullptr)},
              {"instantaneous", held_out_json(&cell.instantaneous)},
              {"corridor_coverage", cell.coverage ? coverage_json(*cell.coverage) : json()}};
    if (cell.coverage && cell.n_turns >= app::kCoverageMinTurns && cell.coverage->total &&
        cell.coverage->share() < 0.7)
      ++below_70;
    cells.push_back(std::move(j));
  }
  json out = {
      {"scoring", "leave_one_out"}, {"default_metric", "path_m"}, {"cells", std::move(cells)}};
  for (const auto& [name, method] : {std::pair{"avk", kin::PredictionMethod::avk},
                                     {"model", kin::PredictionMethod::model},
                                     {"instantaneous", kin::PredictionMethod::instantaneous}}) {
    out["median_path_m"][name] =
        optional_json(kin::median_held_out(c.predictive, method, kin::PathMetric::path_distance));
    out["median_yx_mse_m2"][name] =
        optional_json(kin::median_held_out(c.predictive, method, kin::PathMetric::yx_mse));
  }
  out["corridor"] = coverage_json(kin::total_coverage(c.predictive, app::kCoverageMinTurns));
  out["corridor"]["share_nominal"] = c.corridor_share;
  out["corridor"]["min_turns"] = app::kCoverageMinTurns;
  out["corridor"]["cells_below_70_pct"] = below_70;
  return out;
}

json test_cells_json(const app::Comparison& c) {
  json cells = json::array();
  for (const auto& cell : c.test_cells)
    cells.push_back({{"speed_mps", cell.speed_mps},
                     {"dheading_deg", cell.dheading_deg},
                     {"n_turns", cell.n_turns},
                     {"on_grid", cell.on_grid},
                     {"span_m", cell.span_m},
                     {"avk", held_out_json(&cell.avk)},
                     {"model", held_out_json(cell.model ? &*cell.model : nullptr)},
                     {"instantaneous", held_out_json(&cell.instantaneous)}});
  return cells;
}

json speed_change_json(const std::vector<kin::SpeedChangeCellScores>& cells) {
  using M = kin::SpeedChangeMethod;
  json jc = json::array();
  for (const auto& c : cells) {
    json j = {{"from_mps", c.from_mps},
              {"to_mps", c.to_mps},
              {"dheading_deg", c.dheading_deg},
              {"n_turns", c.n_turns},
              {"span_m", c.span_m}};
    for (const M m : kin::kSpeedChangeMethods) {
      const kin::HeldOutScores* s = kin::scores_of(c, m);
      j[kin::to_string(m)] =
          s && !s->path_m.empty() ? json{{"path_m", mean_sd_json(s->path())}} : json();
    }
    jc.push_back(std::move(j));
  }
  json out = {{"scoring", "held_out"}, {"metric", "path_m"}, {"cells", std::move(jc)}};
  for (const M m : kin::kSpeedChangeMethods)
    out["median_path_m"][kin::to_string(m)] =
        optional_json(kin::median_speed_change_path_m(cells, m));
  return out;
}

json comparison_json(const app::Comparison& c) {
  json out = {{"vehicle_id", c.vehicle_id}, {"model_id", c.model ? json(c.model->id) : json()}};
  if (!c.speed_change.empty()) out["speed_change"] = speed_change_json(c.speed_change);
  if (!c.test_cells.empty()) out["test"] = {{"cells", test_cells_json(c)}};
  // The fair comparison first; "cells" and the medians below are the thesis' in-sample table.
  out["predictive"] = predictive_json(c);
  out["in_sample_scoring"] = "thesis: AVK = spread of the cell's turns about their own mean";
  json jc = json::array();
  for (const auto& cell : c.cells) {
    json j = {{"speed_mps", cell.speed_mps},
              {"dheading_deg", cell.dheading_deg},
              {"n_turns", cell.n_turns},
              {"avk", error_json(cell.avk)},
              {"instantaneous", error_json(cell.instantaneous)},
              {"model", optional_error_json(cell.model)},
              {"outliers", std::count(cell.outlier.begin(), cell.outlier.end(), true)}};
    if (cell.without_outliers) {
      const auto& w = *cell.without_outliers;
      j["without_outliers"] = {{"n_turns", w.n_turns},
                               {"avk", error_json(w.avk)},
                               {"instantaneous", error_json(w.instantaneous)},
                               {"model", optional_error_json(w.model)}};
    }
    jc.push_back(std::move(j));
  }
  out["cells"] = std::move(jc);
  for (const auto& [name, method] : {std::pair{"avk", kin::PredictionMethod::avk},
                                     {"model", kin::PredictionMethod::model},
                                     {"instantaneous", kin::PredictionMethod::instantaneous}}) {
    out["median_mse_m2"][name] = optional_json(kin::median_mse_m2(c.cells, method));
    out["median_mse_without_outliers_m2"][name] =
        optional_json(kin::median_mse_m2(c.cells, method, true));
  }
  return out;
}

}  // namespace avk::server
