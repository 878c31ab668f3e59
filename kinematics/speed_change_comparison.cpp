#include "kinematics/speed_change_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/retimed_turn.hpp"
#include "kinematics/speed_change_table.hpp"

namespace avk::kinematics {

StationedPath stationed_by_speed(const TurnSequence& turn) {
  const TurnSequence norm = turn.meta().normalized ? turn : turn.normalized();
  const auto& samples = norm.samples();
  if (samples.empty()) throw std::invalid_argument("a turn without samples has no path");
  StationedPath p;
  double s = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i > 0) {
      const double dt = samples[i].t_s - samples[i - 1].t_s;
      s += 0.5 * (std::max(0.0, samples[i].speed_mps) + std::max(0.0, samples[i - 1].speed_mps)) *
           dt;
    }
    p.s_m.push_back(s);
    p.points.push_back({samples[i].x_m, samples[i].y_m});
  }
  return p;
}

const char* to_string(SpeedChangeMethod m) {
  switch (m) {
    case SpeedChangeMethod::measured:
      return "measured";
    case SpeedChangeMethod::retimed_measured:
      return "retimed_measured";
    case SpeedChangeMethod::retimed_model:
      return "retimed_model";
    case SpeedChangeMethod::model:
      return "model";
    case SpeedChangeMethod::constant_speed:
      return "constant_speed";
    case SpeedChangeMethod::instantaneous:
      return "instantaneous";
  }
  return "?";
}

const HeldOutScores* scores_of(const SpeedChangeCellScores& c, SpeedChangeMethod m) {
  const auto opt = [](const std::optional<HeldOutScores>& s) { return s ? &*s : nullptr; };
  switch (m) {
    case SpeedChangeMethod::measured:
      return opt(c.measured);
    case SpeedChangeMethod::retimed_measured:
      return opt(c.retimed_measured);
    case SpeedChangeMethod::retimed_model:
      return opt(c.retimed_model);
    case SpeedChangeMethod::model:
      return opt(c.model);
    case SpeedChangeMethod::constant_speed:
      return opt(c.constant_speed);
    case SpeedChangeMethod::instantaneous:
      return &c.instantaneous;
  }
  return nullptr;
}

std::optional<double> median_speed_change_path_m(const std::vector<SpeedChangeCellScores>& cells,
                                                 SpeedChangeMethod method) {
  return median_over(cells, [&](const SpeedChangeCellScores& c) -> std::optional<double> {
    const HeldOutScores* s = scores_of(c, method);
    if (!s || s->path_m.empty()) return std::nullopt;
    return s->path().mean;
  });
}

std::vector<SpeedChangeCellScores> compare_speed_changes(
    const std::vector<TurnSequence>& turns, const Ckt& table,
    const std::optional<SpeedResponse>& model_response, const SpeedChangePredictor* model,
    const CktOptions& options) {
  std::vector<TurnSequence> sc;
  for (const auto& t : turns) {
    if (t.meta().status == TurnStatus::ok && t.meta().speed_after_mps)
      sc.push_back(t.meta().normalized ? t : t.normalized());
  }
  // Cells of (u0, u1, |dheading|) with the indices of their turns.
  std::vector<SpeedChangeCellScores> cells;
  std::vector<std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < sc.size(); ++i) {
    const TurnMeta& m = sc[i].meta();
    const double d = std::abs(m.goal_dheading_deg);
    std::size_t k = 0;
    while (k < cells.size() &&
           !(within_match(cells[k].from_mps, m.commanded_speed_mps, options.speed_match_mps) &&
             within_match(cells[k].to_mps, *m.speed_after_mps, options.speed_match_mps) &&
             within_match(cells[k].dheading_deg, d, options.dheading_match_deg)))
      ++k;
    if (k == cells.size()) {
      SpeedChangeCellScores c;
      c.from_mps = m.commanded_speed_mps;
      c.to_mps = *m.speed_after_mps;
      c.dheading_deg = d;
      cells.push_back(c);
      members.emplace_back();
    }
    members[k].push_back(i);
  }
  const auto range = table.speed_range_mps();
  for (std::size_t k = 0; k < cells.size(); ++k) {
    SpeedChangeCellScores& c = cells[k];
    const double goal = c.dheading_deg;
    std::vector<StationedPath> observed;
    for (std::size_t i : members[k])
      observed.push_back(stationed_by_speed(sc[i]));
    c.n_turns = observed.size();
    c.span_m = longest_m(observed);
    const auto score = [&](std::optional<HeldOutScores>& s, const Polyline& p, std::size_t j) {
      if (!s) s.emplace();
      s->path_m.push_back(
          mean_path_distance_m(stationed_by_length(p), observed[j], goal, c.span_m));
    };
    std::optional<TurnPrediction> base;
    if (range && c.from_mps >= range->first - 1e-9 && c.from_mps <= range->second + 1e-9)
      base = table.query(c.from_mps, goal);
    std::optional<Polyline> model_path;
    if (model && *model) model_path = (*model)(c.from_mps, c.to_mps, goal);
    std::optional<Polyline> retimed_model;
    if (base && model_response)
      retimed_model = retime_turn(*base, c.from_mps, c.to_mps, *model_response).trajectory;
    for (std::size_t j = 0; j < members[k].size(); ++j) {
      const std::size_t held_out = members[k][j];
      std::vector<TurnSequence> others;
      for (std::size_t i = 0; i < sc.size(); ++i)
        if (i != held_out) others.push_back(sc[i]);
      c.instantaneous.path_m.push_back(
          mean_path_distance_m(instantaneous_path(), observed[j], goal, c.span_m));
      const SpeedChangeTable measured = SpeedChangeTable::build(others, options);
      if (const auto m = measured.query(c.from_mps, c.to_mps, goal))
        score(c.measured, m->trajectory, j);
      if (base) {
        if (const auto r = measured_speed_response(others))
          score(c.retimed_measured, retime_turn(*base, c.from_mps, c.to_mps, *r).trajectory, j);
      }
      if (retimed_model) score(c.retimed_model, *retimed_model, j);
      if (base) score(c.constant_speed, base->trajectory, j);
      if (model_path) score(c.model, *model_path, j);
    }
  }
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) {
    if (a.from_mps != b.from_mps) return a.from_mps > b.from_mps;
    if (a.to_mps != b.to_mps) return a.to_mps < b.to_mps;
    return a.dheading_deg < b.dheading_deg;
  });
  return cells;
}

}  // namespace avk::kinematics
