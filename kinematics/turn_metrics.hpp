#pragma once
// The thesis's comparison of prediction methods (§5.2, Figures 5-7 and 5-8): mean squared error
// of y between two turns on a common x grid, with the mean turn taken as the truth. The AVK error
// is how far a single stored turn is from the mean; the instantaneous error is how far the current
// practice (a straight line at the goal heading from the start) is.

#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/mean_turn.hpp"

namespace avk::kinematics {

// Mean of squared y differences over the common x domain. The curves must have the same step and
// grids aligned (x0 differing by a whole number of steps); throws std::invalid_argument otherwise,
// for an empty curve, or when the x domains do not overlap.
double mse_m2(const XGridCurve& a, const XGridCurve& b);

// Two normalised turns on their common x domain, built as for the mean turn of the pair: both
// resampled every step_m and extended along the goal heading to the larger of their largest x (or,
// for a goal the ray cannot extend to, cut at the smaller). Symmetric in a and b.
double mse_m2(const Polyline& a, const Polyline& b, double goal_dheading_deg, double step_m = 0.01);

// The instantaneous-turn assumption: a ray from the origin along the goal heading, y = x cot|goal|,
// on the grid 0..x_max_m. A ray with no +x component (|goal| = 0 or >= 180) has no y(x) beyond
// its start, so the curve is the single point (0, 0).
XGridCurve instantaneous_turn(double goal_dheading_deg, double x_max_m, double step_m = 0.01);

struct CellErrors {
  XGridCurve mean;
  std::vector<double> per_turn_mse_m2;  // in the order of the input turns
  double avk_error_m2 = 0.0;
  // NaN when the instantaneous turn has no y(x) (|goal| = 0 or >= 180): a y-error against its
  // single point would read as a perfect prediction.
  double instantaneous_mse_m2 = 0.0;
};

// AVK error = average over the turns of MSE(turn extended as in the mean, mean); instantaneous =
// MSE(ray, mean). Both on the mean's x domain. Throws std::invalid_argument as mean_turn does.
CellErrors cell_errors(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                       const MeanTurnOptions& options = {});

}  // namespace avk::kinematics
