#include "kinematics/table_evaluation.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/turn_metrics.hpp"

namespace avk::kinematics {

std::vector<TestCell> evaluate_table(const Ckt& table, const std::vector<TurnSequence>& test_turns,
                                     const TurnPredictor* model, const PredictiveOptions& options) {
  const auto range = table.speed_range_mps();
  struct Group {
    double u, d;
    std::vector<TurnSequence> turns;
  };
  std::vector<Group> groups;
  for (const auto& t : test_turns) {
    if (t.meta().status != TurnStatus::ok) continue;
    const double u = t.meta().commanded_speed_mps, d = std::abs(t.meta().goal_dheading_deg);
    if (!range || u < range->first - 1e-9 || u > range->second + 1e-9) continue;
    auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) {
      return std::abs(x.u - u) <= 0.01 && std::abs(x.d - d) <= 0.1;
    });
    if (g == groups.end()) {
      groups.push_back({u, d, {}});
      g = groups.end() - 1;
    }
    g->turns.push_back(t.meta().normalized ? t : t.normalized());
  }
  std::sort(groups.begin(), groups.end(),
            [](const Group& a, const Group& b) { return a.u != b.u ? a.u < b.u : a.d < b.d; });
  const bool have_model = model != nullptr && static_cast<bool>(*model);
  std::vector<TestCell> out;
  for (const auto& g : groups) {
    TestCell c;
    c.speed_mps = g.u;
    c.dheading_deg = g.d;
    c.n_turns = g.turns.size();
    const auto si = table.speed_index(g.u);
    const auto di = table.dheading_index(g.d);
    c.on_grid = si && di && table.cell(*si, *di).has_data();
    std::vector<StationedPath> paths;
    for (const auto& t : g.turns)
      paths.push_back(stationed_by_time(t));
    c.span_m = longest_m(paths);
    const TurnPrediction answer = table.query(g.u, g.d);
    const StationedPath avk = stationed_by_length(answer.trajectory);
    const StationedPath ray = instantaneous_path();
    const double gr = deg_to_rad(g.d);
    const Polyline ray_points{{0.0, 0.0}, {c.span_m * std::sin(gr), c.span_m * std::cos(gr)}};
    Polyline model_points;
    std::optional<StationedPath> model_path;
    if (have_model) {
      model_points = (*model)(g.u, g.d);
      if (model_points.size() >= 2) {
        model_path = stationed_by_length(model_points);
        c.model.emplace();
      }
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const Polyline held = g.turns[i].points();
      const auto score = [&](HeldOutScores& s, const StationedPath& p, const Polyline& yx) {
        s.path_m.push_back(
            mean_path_distance_m(p, paths[i], g.d, c.span_m, options.station_step_m));
        s.yx_mse_m2.push_back(yx_mse_or_nan(yx, held, g.d, options.yx_step_m));
      };
      score(c.avk, avk, answer.trajectory);
      score(c.instantaneous, ray, ray_points);
      if (model_path) score(*c.model, *model_path, model_points);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace avk::kinematics
