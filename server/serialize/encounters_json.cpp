#include "server/serialize/encounters.hpp"

#include "server/serialize/currents.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

json calibration_json(const std::vector<app::RiskBin>& bins) {
  json out = json::array();
  for (const auto& b : bins)
    out.push_back({{"lo", b.lo},
                   {"hi", b.hi},
                   {"candidates", b.candidates},
                   {"mean_predicted", b.mean_predicted},
                   {"observed_rate", b.observed_rate}});
  return out;
}

}  // namespace

json encounter_bench_json(const app::EncounterBench& b, const app::EncounterBenchQuery& q) {
  json scenarios = json::array();
  for (const auto& s : b.scenarios) {
    json methods = json::array();
    for (const auto& r : s.methods) {
      methods.push_back({{"method", app::to_string(r.method)},
                         {"chosen_dheading_deg", optional_json(r.chosen_dheading_deg)},
                         {"predicted_cpa_m", optional_json(r.predicted_cpa_m)},
                         {"predicted_edge_cpa_m", optional_json(r.predicted_edge_cpa_m)},
                         {"actual_cpa_m", r.actual_cpa_m},
                         {"violation", r.violation},
                         {"no_maneuver_while_one_existed", r.no_maneuver_while_one_existed},
                         {"unsafe_while_safe_existed", r.unsafe_while_safe_existed},
                         {"chosen_risk", optional_json(r.chosen_risk)},
                         {"colregs_rule", r.colregs_rule.empty() ? json() : json(r.colregs_rule)},
                         {"along_error_m", optional_json(r.along_error_m)},
                         {"cross_error_m", optional_json(r.cross_error_m)}});
    }
    scenarios.push_back({{"name", s.name},
                         {"sea_seed", s.sea_seed},
                         {"standoff_m", s.standoff_m},
                         {"safe_existed", s.safe_existed},
                         {"course_held_cpa_m", s.course_held_cpa_m},
                         {"candidates_deg", s.candidates_deg},
                         {"flown_cpa_m", s.flown_cpa_m},
                         {"methods", methods}});
  }
  json summary = json::array();
  for (const auto& m : b.summary) {
    summary.push_back({{"method", app::to_string(m.method)},
                       {"available", m.available},
                       {"note", m.note},
                       {"model_id", optional_json(m.model_id)},
                       {"scenarios", m.scenarios},
                       {"violations", m.violations},
                       {"violation_rate", m.violation_rate},
                       {"no_maneuver", m.no_maneuver},
                       {"no_maneuver_while_one_existed", m.no_maneuver_while_one_existed},
                       {"unsafe_while_safe_existed", m.unsafe_while_safe_existed},
                       {"mean_abs_dheading_deg", optional_json(m.mean_abs_dheading_deg)},
                       {"mean_cpa_error_m", optional_json(m.mean_cpa_error_m)},
                       {"mean_abs_cpa_error_m", optional_json(m.mean_abs_cpa_error_m)},
                       {"mean_abs_along_error_m", optional_json(m.mean_abs_along_error_m)},
                       {"mean_abs_cross_error_m", optional_json(m.mean_abs_cross_error_m)},
                       {"calibration", calibration_json(m.calibration)}});
  }
  return {{"vehicle_id", q.vehicle_id},
          {"plant", vehicle::to_string(q.setup.vehicle.kind)},
          {"seed", q.seed},
          {"sea_seeds", q.sea_seeds},
          {"max_risk", q.max_risk},
          {"rule", q.corridor_rule ? "corridor" : "risk"},
          {"colregs", q.prefer_starboard},
          {"ray_band", q.ray_band},
          {"candidate_step_deg", q.candidate_step_deg},
          {"current", water_current_json(b.current, "estimated")},
          {"flights", b.flights},
          {"scenarios", scenarios},
          {"summary", summary}};
}

}  // namespace avk::server
