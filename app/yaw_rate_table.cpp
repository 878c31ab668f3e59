#include "app/yaw_rate_table.hpp"

#include <cmath>
#include <stdexcept>

#include "app/context.hpp"
#include "app/models.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/path_metric.hpp"
#include "mission/turn_monitor.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

std::optional<kin::TurnSequence> model_cell_turn(const kin::YawModel& model, double speed_mps,
                                                 double dheading_deg, double initial_yaw_rate_dps) {
  kin::Polyline path;
  try {
    path = kin::predict_normalized_turn(
        model, speed_mps, dheading_deg,
        mission::completion_threshold_deg(mission::CompletionRule{}, dheading_deg), 0.0, 400, false,
        initial_yaw_rate_dps);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
  if (path.size() < 3) return std::nullopt;
  std::vector<kin::TurnSample> samples;
  samples.reserve(path.size());
  double heading = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (k > 0) {
      const double h =
          kin::heading_of_deg(path[k].x_m - path[k - 1].x_m, path[k].y_m - path[k - 1].y_m);
      heading += kin::angle180_deg(h - heading);
    }
    if (!std::isfinite(path[k].x_m) || !std::isfinite(path[k].y_m)) return std::nullopt;
    samples.push_back(
        {static_cast<double>(k) * model.dt_s(), path[k].x_m, path[k].y_m, heading, speed_mps});
  }
  kin::TurnMeta meta;
  meta.mission_id = "model";
  meta.commanded_speed_mps = speed_mps;
  meta.goal_dheading_deg = dheading_deg;
  meta.observed_dheading_deg = heading;
  meta.initial_speed_mps = speed_mps;
  meta.start_time_s = 0.0;
  meta.end_time_s = samples.back().t_s;
  meta.normalized = true;
  meta.initial_yaw_rate_dps = initial_yaw_rate_dps;
  return kin::TurnSequence(std::move(meta), std::move(samples));
}

namespace {

double mean_error_m(const kin::StationedPath& path, const std::vector<kin::StationedPath>& turns,
                    double dheading_deg) {
  const double span = kin::longest_m(turns);
  double sum = 0.0;
  for (const auto& t : turns)
    sum += kin::mean_path_distance_m(path, t, dheading_deg, span);
  return sum / static_cast<double>(turns.size());
}

}  // namespace

Result<YawRateTable> vehicle_yaw_rate_table(Context& ctx, const std::string& vehicle_id,
                                            const YawRateTableOptions& options) {
  // In the water frame where the mission's current is known, as the 2-D table (ckt_tables.hpp).
  std::vector<kin::TurnSequence> turns = store_of(ctx).turns().load_normalized(
      {}, vehicle_id, false, store::TurnFrameChoice::water_where_known);
  std::erase_if(turns,
                [](const kin::TurnSequence& t) { return t.meta().status != kin::TurnStatus::ok; });
  if (turns.empty()) return not_found("vehicle '" + vehicle_id + "' has no ok turns");
  YawRateTable out;
  try {
    out.table = kin::YawRateCkt::build(turns, options.yaw_rates_dps, {}, std::nullopt,
                                       options.match, &out.report);
  } catch (const std::invalid_argument& e) {
    return invalid_argument("yaw_rates", e.what());
  }
  if (options.fill_with_model) {
    const auto m = model_or_latest(ctx, options.model_id, vehicle_id);
    if (!m && options.model_id) return m.error();
    if (m) {
      out.model_id = m->id;
      const kin::YawModel& model = m->model;
      out.table.fill(
          [&](double u, double d, double rate) { return model_cell_turn(model, u, d, rate); });
      for (const auto& slice : out.table.slices()) {
        if (!options.check_model) break;
        for (std::size_t i = 0; i < slice.table.cells().size(); ++i) {
          const kin::CktCell& c = slice.table.cells()[i];
          if (slice.sources[i] != kin::CellSource::measured || c.turns.empty()) continue;
          const auto model_turn =
              model_cell_turn(model, c.speed_mps, c.dheading_deg, slice.initial_yaw_rate_dps);
          if (!model_turn) continue;
          std::vector<kin::StationedPath> measured;
          for (const auto& t : c.turns)
            measured.push_back(kin::stationed_by_time(t));
          ModelCellCheck check;
          check.speed_mps = c.speed_mps;
          check.dheading_deg = c.dheading_deg;
          check.initial_yaw_rate_dps = slice.initial_yaw_rate_dps;
          check.n_turns = c.turns.size();
          check.model_error_m =
              mean_error_m(kin::stationed_by_time(*model_turn), measured, c.dheading_deg);
          check.table_error_m =
              mean_error_m(kin::stationed_by_length(c.trajectory), measured, c.dheading_deg);
          out.model_checks.push_back(check);
        }
      }
    }
  }
  out.coverage = out.table.coverage();
  return out;
}

}  // namespace avk::app
