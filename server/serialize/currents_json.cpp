#include "server/serialize/currents.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

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
                          const std::optional<app::CurrentView>& stored) {
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

json applied_current_json(const app::AppliedCurrent& a) {
  json j = mission_current_json(a.current, a.stored);
  j["water_frame_turns"] = a.water_turns;
  return j;
}

json compensation_comparison_json(const std::string& vehicle_id,
                                  const app::CompensationComparison& c) {
  json turns = json::array();
  for (const auto& t : c.turns)
    turns.push_back({{"turn_id", t.turn_id},
                     {"speed_mps", t.speed_mps},
                     {"dheading_deg", t.dheading_deg},
                     {"uncompensated_m", t.uncompensated_m},
                     {"compensated_m", t.compensated_m}});
  json currents = json::array();
  for (const auto& [mission, e] : c.test_currents) {
    json j = current_estimate_json(e);
    j["mission_id"] = mission;
    currents.push_back(std::move(j));
  }
  return {{"vehicle_id", vehicle_id},
          {"table_missions", c.table_missions},
          {"test_missions", c.test_missions},
          {"table_turns", c.table_turns},
          {"table_water_turns", c.table_water_turns},
          {"test_currents", currents},
          {"turns_outside_table", c.turns_outside_table},
          {"uncompensated_mean_m", c.uncompensated_mean_m},
          {"compensated_mean_m", c.compensated_mean_m},
          {"improvement", c.improvement()},
          {"turns", turns}};
}

json current_json(const std::string& vehicle_id, const app::CurrentView& c) {
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

}  // namespace avk::server
