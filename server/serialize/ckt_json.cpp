#include "server/serialize/ckt.hpp"

#include "kinematics/ckt3_file.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

namespace {

json cell_summary_json(const kin::CktCell& c) {
  return {{"speed_mps", c.speed_mps},
          {"dheading_deg", c.dheading_deg},
          {"n_turns", c.n_turns},
          {"advance_m", mean_sd_json(c.advance_m)},
          {"transfer_m", mean_sd_json(c.transfer_m)},
          {"avk_error_m2", optional_json(c.avk_error_m2)}};
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
          {"pooled_vehicles", t.pooled_vehicles.empty() ? json() : json(t.pooled_vehicles)},
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

}  // namespace avk::server
