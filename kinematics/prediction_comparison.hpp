#pragma once
// The thesis's comparison of prediction methods per CKT cell (§5.2, Figures 5-7, 5-8, A-5..A-7):
// the mean of a cell's observed turns is taken as the truth, and each method is scored by the MSE
// of y on the mean's x grid and by its error in advance and transfer. AVK is scored as the mean
// error of a single stored turn (it predicts with one observation), the black-box model by its
// predicted trajectory, and the current practice by the instantaneous turn. Cells with outlier
// turns (Figure A-5) are also scored with those turns left out, so one bad run cannot decide
// which method looks best.

#include <cstddef>
#include <functional>
#include <optional>
#include <type_traits>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/mean_turn.hpp"
#include "kinematics/median.hpp"

namespace avk::kinematics {

// A trajectory predictor for a normalised right turn of `dheading_deg` (> 0) from a steady course
// at `speed_mps`: the black-box model's prediction (supplied by the caller) — points from the
// origin, ending when the predicted heading is within the completion threshold of the goal.
using TurnPredictor = std::function<Polyline(double speed_mps, double dheading_deg)>;

struct MethodError {
  double mse_m2 = 0.0;  // against the mean turn, on the mean's x grid
  // 100 (1 - mse / instantaneous mse); empty for the instantaneous method itself or when that mse
  // is 0 or NaN.
  std::optional<double> improvement_pct;
  double advance_error_m = 0.0;  // |method advance - mean of the cell's turns' advance|
  double transfer_error_m = 0.0;
};

struct CellComparison {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;
  std::size_t n_turns = 0;
  std::vector<double> per_turn_mse_m2;  // each turn vs the mean, in the cell's turn order
  std::vector<bool> outlier;            // robust flag per turn (robust_outliers)
  XGridCurve mean;                      // the mean turn
  MethodError avk, instantaneous;
  std::optional<MethodError> model;  // empty when no model was given
  // The same with the outlier turns left out (mean recomputed); empty when no turn is an outlier
  // or fewer than min_turns remain.
  struct WithoutOutliers {
    std::size_t n_turns = 0;
    MethodError avk, instantaneous;
    std::optional<MethodError> model;
  };
  std::optional<WithoutOutliers> without_outliers;
};

struct ComparisonOptions {
  std::size_t min_turns = 2;  // cells with fewer turns are skipped (1 is the least used)
  double outlier_z = 3.5;     // modified z-score above which a turn is an outlier
  MeanTurnOptions mean{};     // grid of the mean turn and of every MSE
};

// One entry per cell (row-major, as Ckt::cells) holding at least min_turns turns; cells without
// turns (a table loaded from file) are skipped. The model, when given, is asked once per cell.
// Throws std::invalid_argument, naming the cell, when the model returns fewer than 2 points or a
// non-finite one, and as cell_errors does for unusable turns.
std::vector<CellComparison> compare_predictions(const Ckt& table, const TurnPredictor* model,
                                                const ComparisonOptions& options = {});

// Iglewicz-Hoaglin modified z-score, high side only: z = 0.6745 (v - median) / MAD and v is
// flagged when z > z_threshold. Only large values are flagged because a turn unusually *close* to
// the mean is not suspect. MAD <= mad_floor (0: half the values equal) flags nothing: identical
// turns have per-turn MSEs that differ only by rounding, and z-scores of rounding are arbitrary.
// NaN is never flagged.
std::vector<bool> robust_outliers(const std::vector<double>& values, double z_threshold,
                                  double mad_floor = 0.0);

// The mad_floor compare_predictions uses: per-turn MSEs that differ by less than 1e-12 m^2 (a
// micrometre RMS) differ by rounding, not by how the vehicle turned.
inline constexpr double kOutlierMadFloor_m2 = 1e-12;

enum class PredictionMethod { avk, model, instantaneous };

// The entry of `method` in a per-method record (avk and instantaneous always there, the model
// optional): null for the model when none was compared.
template <class Record>
const auto* method_entry(const Record& record, PredictionMethod method) {
  using Entry = std::remove_cvref_t<decltype(record.avk)>;
  switch (method) {
    case PredictionMethod::avk:
      return static_cast<const Entry*>(&record.avk);
    case PredictionMethod::instantaneous:
      return static_cast<const Entry*>(&record.instantaneous);
    case PredictionMethod::model:
      return record.model ? static_cast<const Entry*>(&*record.model) : nullptr;
  }
  return static_cast<const Entry*>(nullptr);
}

// A method's error in one cell: with drop_outliers the without-outliers result when the cell has
// one (otherwise the full result, which then has no outliers to drop). Null for the model when
// none was compared.
const MethodError* method_error(const CellComparison& cell, PredictionMethod method,
                                bool drop_outliers = false);

// Medians across cells (the summary line under Figure 5-8); cells where the value is missing or
// NaN do not count. Empty when no cell has the value.
std::optional<double> median_mse_m2(const std::vector<CellComparison>& cells,
                                    PredictionMethod method, bool drop_outliers = false);
std::optional<double> median_improvement_pct(const std::vector<CellComparison>& cells,
                                             PredictionMethod method, bool drop_outliers = false);

}  // namespace avk::kinematics
