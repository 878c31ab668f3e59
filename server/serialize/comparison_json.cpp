#include "server/serialize/comparison.hpp"

#include <algorithm>

#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

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
}  // namespace

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
