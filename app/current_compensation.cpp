#include "app/current_compensation.hpp"

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/mission_legs.hpp"
#include "app/store_access.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/path_metric.hpp"
#include "kinematics/water_frame.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

double CompensationComparison::improvement() const {
  return uncompensated_mean_m > 0.0 ? 1.0 - compensated_mean_m / uncompensated_mean_m : 0.0;
}

namespace {

// The table's right turn at the test turn's speed and |goal|, timed, carried by a current given
// in the normalised frame, stationed by its clock as an observed turn is.
kin::StationedPath predicted_path(const kin::Ckt& table, double speed_mps, double dheading_deg,
                                  kin::Point drift_mps) {
  const kin::TurnPrediction p = table.query(speed_mps, std::abs(dheading_deg));
  const kin::PredictedManeuver m =
      kin::timed_maneuver(std::abs(dheading_deg), speed_mps, p.trajectory, p.timing);
  return kin::stationed_by_clock(kin::drifted(m.path, drift_mps), speed_mps);
}

}  // namespace

Result<CompensationComparison> compare_current_compensation(
    Context& ctx, const std::string& vehicle_id, const std::vector<std::int64_t>& table_missions,
    const std::vector<std::int64_t>& test_missions) {
  if (table_missions.empty()) return invalid_argument("missions", "name the table's missions");
  if (test_missions.empty()) return invalid_argument("test_missions", "name the test missions");
  for (const auto id : test_missions)
    if (std::find(table_missions.begin(), table_missions.end(), id) != table_missions.end())
      return invalid_argument("test_missions", "mission " + std::to_string(id) +
                                                   " is in the table; a test needs other turns");
  store::Store& db = store_of(ctx);
  for (const auto& list : {table_missions, test_missions})
    for (const auto id : list)
      if (!db.missions().get(id)) return not_found("no mission " + std::to_string(id));

  CompensationComparison out;
  out.table_missions = table_missions;
  out.test_missions = test_missions;
  const auto ground_turns = db.turns().load_normalized(table_missions, vehicle_id);
  if (ground_turns.empty()) return not_found("the table's missions hold no ok turns");
  const auto water_turns = db.turns().load_normalized(table_missions, vehicle_id, false,
                                                      store::TurnFrameChoice::water_where_known);
  out.table_turns = water_turns.size();
  for (const auto& t : water_turns)
    out.table_water_turns += t.meta().removed_current ? 1 : 0;
  const kin::Ckt ground = kin::Ckt::build(ground_turns);
  const kin::Ckt water = kin::Ckt::build(water_turns);

  double sum_u = 0.0, sum_c = 0.0;
  for (const auto mission : test_missions) {
    auto est = estimate_mission_current(ctx, mission);
    if (!est) return est.error();
    if (!est->result.estimate)
      return not_found("the current of test mission " + std::to_string(mission) +
                       " cannot be estimated: " + est->result.why_not);
    const kin::WaterCurrent c = water_current(*est->result.estimate);
    out.test_currents.emplace_back(mission, *est->result.estimate);
    for_each_mission_turn(db, mission, kin::TurnStatus::ok, [&](const store::TurnRow& row) {
      const auto stored = db.turns().get(row.id);
      if (!stored || !stored->normalized) return;
      const kin::TurnSequence& raw = stored->raw;
      const double speed = raw.meta().commanded_speed_mps;
      const double goal = raw.meta().goal_dheading_deg;
      try {
        const kin::StationedPath observed = kin::stationed_by_time(*stored->normalized);
        const double span = observed.length_m();
        const kin::Point drift =
            kin::current_in_normalized_frame(c, raw.meta().initial_heading_deg, raw.side());
        CompensatedTurn t;
        t.turn_id = row.id;
        t.speed_mps = speed;
        t.dheading_deg = goal;
        t.uncompensated_m = kin::mean_path_distance_m(
            predicted_path(ground, speed, goal, {0.0, 0.0}), observed, std::abs(goal), span);
        t.compensated_m = kin::mean_path_distance_m(predicted_path(water, speed, goal, drift),
                                                    observed, std::abs(goal), span);
        sum_u += t.uncompensated_m;
        sum_c += t.compensated_m;
        out.turns.push_back(t);
      } catch (const kin::CktRangeError&) {
        ++out.turns_outside_table;
      }
    });
  }
  if (!out.turns.empty()) {
    out.uncompensated_mean_m = sum_u / static_cast<double>(out.turns.size());
    out.compensated_mean_m = sum_c / static_cast<double>(out.turns.size());
  }
  return out;
}

}  // namespace avk::app
