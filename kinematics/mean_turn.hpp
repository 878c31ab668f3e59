#pragma once
// The thesis mean turn (§5.2, Figure 5-6): normalised turns resampled to a constant x spacing and
// their y averaged at each x. Turns are extended along the goal heading to the largest x of the
// set so every turn covers the same x domain.
//
// Representing a turn as y(x) has consequences the functions below share:
// - A path that is not single-valued in x (the lead-in runs up x = 0; turns past 90 deg may
//   curl) is read at its *first crossing* of each x: the grid value at x is y where the path first
//   reaches x. So y(0) is the start point and the grid value just above 0 is taken where the path
//   leaves the lead-in, not on it.
// - x that goes slightly negative at the start (position noise on the lead-in) is harmless: the
//   grid starts at x = 0, which takes the first point's y, and x is only "reached" once the path
//   gets past the largest x it has seen so far, so backward excursions are ignored.
// - Only |goal_dheading_deg| is used: normalised turns are right turns.
// - Past a turn's own largest x it is extended along a ray from its *last* point at heading
//   |goal|. That ray has no +x component at 180 deg, and close to 180 deg it falls so steeply
//   (|cot| > 11 past 175 deg) that millimetre differences in the turns' largest x become
//   decimetres of y. For |goal| outside (0, kMaxExtendableGoal_deg] nothing is extended: each turn
//   stops at its own largest x and a set is averaged on its common x domain, [0, min over turns of
//   their largest x] (x_margin_m is then ignored).

#include <cstddef>
#include <vector>

#include "kinematics/geometry.hpp"

namespace avk::kinematics {

// Largest |goal| (deg) whose ray is used to extend turns in x; covers the thesis's 170-deg turns.
inline constexpr double kMaxExtendableGoal_deg = 175.0;

// Grids longer than this are refused rather than allocated (10 km at the thesis's 1 cm).
inline constexpr std::size_t kMaxXGridPoints = 1'000'000;

// Whether turns toward this goal are extended along the goal ray (see the file comment).
bool goal_ray_extends_in_x(double goal_dheading_deg);

struct XGridCurve {  // y sampled on x = x0_m + i*step_m
  double x0_m = 0.0;
  double step_m = 0.01;
  std::vector<double> y_m;

  double x_at_m(std::size_t i) const { return x0_m + static_cast<double>(i) * step_m; }
  double x_end_m() const;  // x of the last sample; x0_m when empty
  Polyline points() const;
  bool empty() const { return y_m.empty(); }
};

struct MeanTurnOptions {
  double x_step_m = 0.01;  // thesis: 0.01 m
  // Extend the common domain this far past the largest x of the set (0 = thesis). Ignored when
  // the goal ray does not extend in x.
  double x_margin_m = 0.0;
};

// Number of grid points 0, step, 2 step, ... up to x_max_m (a point within 1e-9 step past x_max_m
// counts, so rounding in x_max_m / step_m does not drop the last one). Throws
// std::invalid_argument for a non-finite or negative x_max_m, a non-positive step or a grid
// longer than kMaxXGridPoints.
std::size_t x_grid_size(double x_max_m, double step_m);

// Largest x the turn reaches, never below 0 (the grid starts at the origin).
double max_x_m(const Polyline& normalized);

// The x extent a set of turns is averaged over: max over turns of max_x_m + margin when the goal
// ray extends in x, else min over turns of max_x_m. Throws std::invalid_argument when empty.
double set_x_max_m(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                   double x_margin_m = 0.0);

// One normalised turn on the x grid from 0 to x_max_m: where the path is not single-valued in x use
// the first crossing; past the turn's own largest x it is extended along the goal heading (a ray
// from its last point at heading |goal_dheading_deg|). When the goal ray does not extend in x the
// curve stops at the turn's own largest x and may be shorter than the grid. One sweep over the
// points and the grid: O(points + grid). Throws std::invalid_argument for < 2 points, non-finite
// coordinates or a bad grid (x_grid_size).
XGridCurve resample_on_x_grid(const Polyline& normalized, double goal_dheading_deg, double x_max_m,
                              double step_m);

// resample_on_x_grid writing the y values into y_out (resized), so a caller looping over
// thousands of turns reuses one buffer instead of allocating per turn.
void resample_on_x_grid_into(const Polyline& normalized, double goal_dheading_deg, double x_max_m,
                             double step_m, std::vector<double>& y_out);

// Each normalised turn extended along the goal heading to the largest x of the set (+ margin) and
// resampled on a constant x grid; y averaged per x. For a goal the ray cannot extend to
// (goal_ray_extends_in_x) the average is over the common x domain instead. Throws
// std::invalid_argument for no turns or a turn with < 2 points.
XGridCurve mean_turn(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                     const MeanTurnOptions& options = {});

}  // namespace avk::kinematics
