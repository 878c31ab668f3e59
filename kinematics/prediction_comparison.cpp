#include "kinematics/prediction_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_metrics.hpp"

namespace avk::kinematics {

namespace {

// 0.6745 = the 0.75 quantile of the standard normal: makes MAD a consistent estimate of sigma.
constexpr double kMadToSigma = 0.6745;

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

std::string cell_name(const CktCell& c) {
  return "cell (" + fmt(c.speed_mps) + " m/s, " + fmt(c.dheading_deg) + " deg)";
}

// A bad prediction would otherwise surface as a resampling error with no hint of which cell or
// which method produced it.
void check_prediction(const Polyline& p, const CktCell& c) {
  if (p.size() < 2) {
    throw std::invalid_argument("prediction comparison: " + cell_name(c) +
                                ": the model predicted " + std::to_string(p.size()) +
                                " point(s); at least 2 are needed");
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!std::isfinite(p[i].x_m) || !std::isfinite(p[i].y_m)) {
      throw std::invalid_argument("prediction comparison: " + cell_name(c) +
                                  ": the model predicted a non-finite point (index " +
                                  std::to_string(i) + ")");
    }
  }
}

std::optional<double> improvement_pct(double mse_m2, double instantaneous_mse_m2) {
  if (std::isnan(instantaneous_mse_m2) || instantaneous_mse_m2 == 0.0) return std::nullopt;
  return 100.0 * (1.0 - mse_m2 / instantaneous_mse_m2);
}

struct Prediction {
  Polyline trajectory;
  AdvanceTransfer at;
};

struct Scores {
  CellErrors errors;
  MethodError avk, instantaneous;
  std::optional<MethodError> model;
};

Scores score(const std::vector<Polyline>& turns, const std::vector<AdvanceTransfer>& at,
             double dheading_deg, const std::optional<Prediction>& prediction,
             const MeanTurnOptions& options) {
  Scores s{cell_errors(turns, dheading_deg, options), {}, {}, {}};
  const double n = static_cast<double>(at.size());
  double mean_advance = 0.0, mean_transfer = 0.0;
  for (const auto& a : at) {
    mean_advance += a.advance_m / n;
    mean_transfer += a.transfer_m / n;
  }
  const double inst_mse = s.errors.instantaneous_mse_m2;

  s.avk.mse_m2 = s.errors.avk_error_m2;
  s.avk.improvement_pct = improvement_pct(s.avk.mse_m2, inst_mse);
  for (const auto& a : at) {
    s.avk.advance_error_m += std::abs(a.advance_m - mean_advance) / n;
    s.avk.transfer_error_m += std::abs(a.transfer_m - mean_transfer) / n;
  }

  // The instantaneous turn pivots on the spot: no advance, no transfer.
  s.instantaneous.mse_m2 = inst_mse;
  s.instantaneous.advance_error_m = std::abs(mean_advance);
  s.instantaneous.transfer_error_m = std::abs(mean_transfer);

  if (prediction) {
    // Same origin, step and x_max as the mean, so the two grids coincide point for point.
    const XGridCurve predicted = resample_on_x_grid(prediction->trajectory, dheading_deg,
                                                    s.errors.mean.x_end_m(), s.errors.mean.step_m);
    MethodError m;
    m.mse_m2 = mse_m2(predicted, s.errors.mean);
    m.improvement_pct = improvement_pct(m.mse_m2, inst_mse);
    m.advance_error_m = std::abs(prediction->at.advance_m - mean_advance);
    m.transfer_error_m = std::abs(prediction->at.transfer_m - mean_transfer);
    s.model = m;
  }
  return s;
}

}  // namespace

std::vector<CellComparison> compare_predictions(const Ckt& table, const TurnPredictor* model,
                                                const ComparisonOptions& options) {
  const std::size_t min_turns = std::max<std::size_t>(1, options.min_turns);
  const bool have_model = model != nullptr && static_cast<bool>(*model);
  std::vector<CellComparison> out;
  std::vector<Polyline> paths, kept_paths;
  std::vector<AdvanceTransfer> at, kept_at;
  for (const CktCell& cell : table.cells()) {
    if (cell.turns.size() < min_turns) continue;
    paths.clear();
    at.clear();
    for (const auto& t : cell.turns) {
      paths.push_back(t.points());
      at.push_back(advance_transfer(paths.back()));
    }
    std::optional<Prediction> prediction;
    if (have_model) {
      Polyline p = (*model)(cell.speed_mps, cell.dheading_deg);
      check_prediction(p, cell);
      const AdvanceTransfer pat = advance_transfer(p);
      prediction = Prediction{std::move(p), pat};
    }

    Scores s = score(paths, at, cell.dheading_deg, prediction, options.mean);
    CellComparison c;
    c.speed_mps = cell.speed_mps;
    c.dheading_deg = cell.dheading_deg;
    c.n_turns = paths.size();
    c.per_turn_mse_m2 = std::move(s.errors.per_turn_mse_m2);
    c.outlier = robust_outliers(c.per_turn_mse_m2, options.outlier_z, kOutlierMadFloor_m2);
    c.mean = std::move(s.errors.mean);
    c.avk = s.avk;
    c.instantaneous = s.instantaneous;
    c.model = s.model;

    kept_paths.clear();
    kept_at.clear();
    for (std::size_t i = 0; i < paths.size(); ++i) {
      if (c.outlier[i]) continue;
      kept_paths.push_back(paths[i]);
      kept_at.push_back(at[i]);
    }
    if (kept_paths.size() < paths.size() && kept_paths.size() >= min_turns) {
      const Scores k = score(kept_paths, kept_at, cell.dheading_deg, prediction, options.mean);
      c.without_outliers =
          CellComparison::WithoutOutliers{kept_paths.size(), k.avk, k.instantaneous, k.model};
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<bool> robust_outliers(const std::vector<double>& values, double z_threshold,
                                  double mad_floor) {
  std::vector<bool> flagged(values.size(), false);
  const std::optional<double> median = median_of(values);
  if (!median) return flagged;
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (double v : values)
    deviations.push_back(std::abs(v - *median));
  const std::optional<double> mad = median_of(std::move(deviations));
  if (!mad || !(*mad > std::max(mad_floor, 0.0))) return flagged;
  for (std::size_t i = 0; i < values.size(); ++i)
    flagged[i] = kMadToSigma * (values[i] - *median) / *mad > z_threshold;
  return flagged;
}

const MethodError* method_error(const CellComparison& cell, PredictionMethod method,
                                bool drop_outliers) {
  if (drop_outliers && cell.without_outliers) return method_entry(*cell.without_outliers, method);
  return method_entry(cell, method);
}

std::optional<double> median_mse_m2(const std::vector<CellComparison>& cells,
                                    PredictionMethod method, bool drop_outliers) {
  return median_over(cells, [&](const CellComparison& c) -> std::optional<double> {
    const MethodError* e = method_error(c, method, drop_outliers);
    return e ? std::optional(e->mse_m2) : std::nullopt;
  });
}

std::optional<double> median_improvement_pct(const std::vector<CellComparison>& cells,
                                             PredictionMethod method, bool drop_outliers) {
  return median_over(cells, [&](const CellComparison& c) -> std::optional<double> {
    const MethodError* e = method_error(c, method, drop_outliers);
    return e ? e->improvement_pct : std::nullopt;
  });
}

}  // namespace avk::kinematics
