#include "kinematics/predictive_comparison.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"
#include "kinematics/mean_turn.hpp"
#include "kinematics/turn_metrics.hpp"

namespace avk::kinematics {

namespace {

std::string cell_name(const CktCell& c) {
  std::ostringstream o;
  o << "cell (" << c.speed_mps << " m/s, " << c.dheading_deg << " deg)";
  return o.str();
}

void check_model_path(const Polyline& p, const CktCell& c) {
  if (p.size() < 2)
    throw std::invalid_argument("predictive comparison: " + cell_name(c) +
                                ": the model predicted " + std::to_string(p.size()) +
                                " point(s); at least 2 are needed");
  for (const auto& q : p) {
    if (!std::isfinite(q.x_m) || !std::isfinite(q.y_m))
      throw std::invalid_argument("predictive comparison: " + cell_name(c) +
                                  ": the model predicted a non-finite point");
  }
}

// The instantaneous ray as a polyline long enough for the y(x) metric's extension.
Polyline ray_polyline(double goal_dheading_deg, double length_m) {
  const double g = deg_to_rad(goal_dheading_deg);
  return {{0.0, 0.0}, {length_m * std::sin(g), length_m * std::cos(g)}};
}

}  // namespace

std::vector<PredictiveCell> compare_predictive(const Ckt& table, const TurnPredictor* model,
                                               const PredictiveOptions& options) {
  const std::size_t min_turns = std::max<std::size_t>(2, options.min_turns);
  const bool have_model = model != nullptr && static_cast<bool>(*model);
  std::vector<PredictiveCell> out;
  for (const CktCell& cell : table.cells()) {
    if (cell.turns.size() < min_turns) continue;
    const double goal = cell.dheading_deg;
    std::vector<StationedPath> paths;
    std::vector<Polyline> points;
    for (const auto& t : cell.turns) {
      paths.push_back(stationed_by_time(t));
      points.push_back(t.points());
    }
    PredictiveCell pc;
    pc.speed_mps = cell.speed_mps;
    pc.dheading_deg = goal;
    pc.n_turns = paths.size();
    pc.span_m = longest_m(paths);
    const StationedPath ray = instantaneous_path();
    const Polyline ray_points = ray_polyline(goal, pc.span_m);
    std::optional<StationedPath> model_path;
    Polyline model_points;
    if (have_model) {
      model_points = (*model)(cell.speed_mps, goal);
      check_model_path(model_points, cell);
      model_path = stationed_by_length(model_points);
      pc.model.emplace();
    }
    if (paths.size() >= 3) pc.coverage.emplace();
    std::vector<StationedPath> others;
    std::vector<Polyline> other_points;
    for (std::size_t i = 0; i < paths.size(); ++i) {
      others.clear();
      other_points.clear();
      for (std::size_t j = 0; j < paths.size(); ++j) {
        if (j == i) continue;
        others.push_back(paths[j]);
        other_points.push_back(points[j]);
      }
      const StationedPath avk = mean_path_at_stations(others, goal, options.station_step_m);
      const Polyline avk_yx = mean_turn(other_points, goal, {options.yx_step_m, 0.0}).points();
      const auto score = [&](HeldOutScores& s, const StationedPath& p, const Polyline& yx) {
        s.path_m.push_back(
            mean_path_distance_m(p, paths[i], goal, pc.span_m, options.station_step_m));
        s.yx_mse_m2.push_back(yx_mse_or_nan(yx, points[i], goal, options.yx_step_m));
      };
      score(pc.avk, avk, avk_yx);
      score(pc.instantaneous, ray, ray_points);
      if (model_path) score(*pc.model, *model_path, model_points);
      if (pc.coverage) {
        if (const auto c = corridor_of(others, avk, goal)) {
          *pc.coverage += corridor_coverage(paths[i], avk, *c, goal, options.corridor_share,
                                            options.station_step_m);
        }
      }
    }
    out.push_back(std::move(pc));
  }
  return out;
}

double yx_mse_or_nan(const Polyline& a, const Polyline& b, double goal_dheading_deg,
                     double step_m) {
  try {
    return mse_m2(a, b, goal_dheading_deg, step_m);
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

const HeldOutScores* held_out_scores(const PredictiveCell& cell, PredictionMethod method) {
  return method_entry(cell, method);
}

std::optional<double> median_held_out(const std::vector<PredictiveCell>& cells,
                                      PredictionMethod method, PathMetric metric) {
  return median_over(cells, [&](const PredictiveCell& c) -> std::optional<double> {
    const HeldOutScores* s = method_entry(c, method);
    if (!s) return std::nullopt;
    return metric == PathMetric::path_distance ? s->path().mean : s->yx_mse().mean;
  });
}

Coverage total_coverage(const std::vector<PredictiveCell>& cells, std::size_t min_turns) {
  Coverage total;
  for (const auto& c : cells) {
    if (c.coverage && c.n_turns >= min_turns) total += *c.coverage;
  }
  return total;
}

}  // namespace avk::kinematics
