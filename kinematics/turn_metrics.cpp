#include "kinematics/turn_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

namespace {

// Mean squared difference of the first n values of two y arrays sampled on the same grid.
double mse_prefix(const std::vector<double>& a, const std::vector<double>& b, std::size_t n) {
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = a[k] - b[k];
    sum += d * d;
  }
  return sum / static_cast<double>(n);
}

}  // namespace

double mse_m2(const XGridCurve& a, const XGridCurve& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("mse_m2: empty curve");
  const double step = a.step_m;
  if (!(step > 0.0) || std::abs(a.step_m - b.step_m) > 1e-9 * step) {
    throw std::invalid_argument("mse_m2: curves have different x steps");
  }
  const double offset_steps = (b.x0_m - a.x0_m) / step;
  const double whole_steps = std::round(offset_steps);
  if (std::abs(offset_steps - whole_steps) > 1e-6) {
    throw std::invalid_argument("mse_m2: curves are sampled on x grids that are not aligned");
  }
  // Index in a of b's first sample (may be negative: b starts first).
  const auto shift = static_cast<long long>(whole_steps);
  const long long first = std::max(0LL, shift);
  const long long last =
      std::min(static_cast<long long>(a.y_m.size()), shift + static_cast<long long>(b.y_m.size()));
  if (last <= first) throw std::invalid_argument("mse_m2: curves have no common x domain");
  double sum = 0.0;
  for (long long i = first; i < last; ++i) {
    const double d =
        a.y_m[static_cast<std::size_t>(i)] - b.y_m[static_cast<std::size_t>(i - shift)];
    sum += d * d;
  }
  return sum / static_cast<double>(last - first);
}

double mse_m2(const Polyline& a, const Polyline& b, double goal_dheading_deg, double step_m) {
  const double xa = max_x_m(a);
  const double xb = max_x_m(b);
  const double x_max =
      goal_ray_extends_in_x(goal_dheading_deg) ? std::max(xa, xb) : std::min(xa, xb);
  std::vector<double> ya, yb;
  resample_on_x_grid_into(a, goal_dheading_deg, x_max, step_m, ya);
  resample_on_x_grid_into(b, goal_dheading_deg, x_max, step_m, yb);
  return mse_prefix(ya, yb, std::min(ya.size(), yb.size()));
}

XGridCurve instantaneous_turn(double goal_dheading_deg, double x_max_m, double step_m) {
  const double g = std::abs(goal_dheading_deg);
  XGridCurve ray;
  ray.step_m = step_m;
  const std::size_t n = x_grid_size(x_max_m, step_m);
  if (!(g > 0.0 && g < 180.0)) {
    ray.y_m.assign(1, 0.0);
    return ray;
  }
  const double dy_per_dx = std::cos(deg_to_rad(g)) / std::sin(deg_to_rad(g));
  ray.y_m.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    ray.y_m[k] = ray.x_at_m(k) * dy_per_dx;
  return ray;
}

CellErrors cell_errors(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                       const MeanTurnOptions& options) {
  CellErrors out;
  out.mean = mean_turn(normalized_turns, goal_dheading_deg, options);
  const double x_max = out.mean.x_end_m();
  out.per_turn_mse_m2.reserve(normalized_turns.size());
  std::vector<double> y;
  double sum = 0.0;
  for (const auto& turn : normalized_turns) {
    resample_on_x_grid_into(turn, goal_dheading_deg, x_max, options.x_step_m, y);
    const double e = mse_prefix(y, out.mean.y_m, std::min(y.size(), out.mean.y_m.size()));
    out.per_turn_mse_m2.push_back(e);
    sum += e;
  }
  out.avk_error_m2 = sum / static_cast<double>(normalized_turns.size());
  const double g = std::abs(goal_dheading_deg);
  out.instantaneous_mse_m2 =
      g > 0.0 && g < 180.0
          ? mse_m2(instantaneous_turn(goal_dheading_deg, x_max, options.x_step_m), out.mean)
          : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace avk::kinematics
