#include "server/serialize/maneuvers.hpp"

#include <stdexcept>
#include <string_view>

#include "kinematics/colregs.hpp"
#include "kinematics/position_band.hpp"
#include "server/serialize/currents.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

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
              {"live_contacts", e.live_contact_names},
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

json maneuver_simulation_json(const app::SimulatedManeuver& m, const SimulateRequest& request,
                              const std::string& vehicle_id, bool station_setup,
                              const std::string& default_setup) {
  const app::SimulatedManeuverQuery& q = request.query;
  json j =
      simulated_maneuver_json(m, request.own_position, request.standoff_m, request.path_step_s);
  j["vehicle_id"] = vehicle_id;
  j["sim_vehicle"] = vehicle::to_string(q.setup.vehicle.kind);
  j["station_setup"] = station_setup;
  if (!station_setup)
    j["note"] = "the vehicle is not the station's simulated one: flown with the default " +
                default_setup + " setup";
  j["seed"] = q.seed;
  j["dheading_deg"] = q.dheading_deg;
  j["speed_mps"] = q.speed_mps.value_or(q.own_speed_mps);
  return j;
}

json maneuver_flight_json(const app::SimulatedManeuver& m, const SimulateRequest& request) {
  const app::SimulatedManeuverQuery& q = request.query;
  json j =
      simulated_maneuver_json(m, request.own_position, request.standoff_m, request.path_step_s);
  j["sim_vehicle"] = vehicle::to_string(q.setup.vehicle.kind);
  j["seed"] = q.seed;
  j["dheading_deg"] = q.dheading_deg;
  j["horizon_s"] = q.horizon_s;
  j["settle_s"] = m.settle_s;
  return j;
}

}  // namespace avk::server
