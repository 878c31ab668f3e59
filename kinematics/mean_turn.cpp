#include "kinematics/mean_turn.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

namespace {

// x_max_m / step_m rarely lands exactly on an integer; grid points this close past a reached x
// count as reached, so a turn whose largest x is the set's largest x covers the whole grid.
constexpr double kGridEps = 1e-9;

// The message is only built on failure: this runs once per turn of a 10,000-turn table.
void check_turn(const Polyline& turn, const char* context, std::size_t index) {
  if (turn.size() < 2) {
    throw std::invalid_argument(std::string(context) + ": turn " + std::to_string(index) + " has " +
                                std::to_string(turn.size()) + " point(s); at least 2 are needed");
  }
}

}  // namespace

bool goal_ray_extends_in_x(double goal_dheading_deg) {
  const double g = std::abs(goal_dheading_deg);
  return g > 0.0 && g <= kMaxExtendableGoal_deg;
}

double XGridCurve::x_end_m() const {
  return y_m.empty() ? x0_m : x_at_m(y_m.size() - 1);
}

Polyline XGridCurve::points() const {
  Polyline out;
  out.reserve(y_m.size());
  for (std::size_t i = 0; i < y_m.size(); ++i)
    out.push_back({x_at_m(i), y_m[i]});
  return out;
}

std::size_t x_grid_size(double x_max_m, double step_m) {
  if (!std::isfinite(step_m) || !(step_m > 0.0)) {
    throw std::invalid_argument("x grid: step must be a positive number of metres, got " +
                                std::to_string(step_m));
  }
  if (!std::isfinite(x_max_m) || x_max_m < 0.0) {
    throw std::invalid_argument("x grid: x_max must be finite and >= 0, got " +
                                std::to_string(x_max_m));
  }
  const double intervals = std::floor(x_max_m / step_m + kGridEps);
  if (intervals + 1.0 > static_cast<double>(kMaxXGridPoints)) {
    throw std::invalid_argument("x grid: " + std::to_string(x_max_m) + " m at " +
                                std::to_string(step_m) + " m steps exceeds " +
                                std::to_string(kMaxXGridPoints) + " points");
  }
  return static_cast<std::size_t>(intervals) + 1;
}

double max_x_m(const Polyline& normalized) {
  double x_max = 0.0;
  for (const Point& p : normalized)
    x_max = std::max(x_max, p.x_m);
  return x_max;
}

double set_x_max_m(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                   double x_margin_m) {
  if (normalized_turns.empty()) {
    throw std::invalid_argument("mean turn: no turns given");
  }
  if (!std::isfinite(x_margin_m) || x_margin_m < 0.0) {
    throw std::invalid_argument("mean turn: x margin must be finite and >= 0");
  }
  if (goal_ray_extends_in_x(goal_dheading_deg)) {
    double x_max = 0.0;
    for (const auto& t : normalized_turns)
      x_max = std::max(x_max, max_x_m(t));
    return x_max + x_margin_m;
  }
  double x_max = max_x_m(normalized_turns.front());
  for (const auto& t : normalized_turns)
    x_max = std::min(x_max, max_x_m(t));
  return x_max;
}

void resample_on_x_grid_into(const Polyline& normalized, double goal_dheading_deg, double x_max_m,
                             double step_m, std::vector<double>& y_out) {
  check_turn(normalized, "resample_on_x_grid", 0);
  const std::size_t n = x_grid_size(x_max_m, step_m);
  const double tol_m = kGridEps * step_m;
  y_out.resize(n);
  const auto grid_x = [step_m](std::size_t k) { return static_cast<double>(k) * step_m; };
  const auto finite = [](const Point& p) { return std::isfinite(p.x_m) && std::isfinite(p.y_m); };

  const Point& p0 = normalized.front();
  if (!finite(p0)) throw std::invalid_argument("resample_on_x_grid: non-finite point 0");
  // reach = the largest x the path has got to so far; every grid point at or below it is filled
  // and only a segment that gets past it can cross a new one (first crossing).
  double reach_m = std::max(p0.x_m, 0.0);
  std::size_t k = 0;
  while (k < n && grid_x(k) <= reach_m + tol_m)
    y_out[k++] = p0.y_m;
  for (std::size_t i = 1; i < normalized.size(); ++i) {
    const Point& b = normalized[i];
    if (!finite(b)) {
      throw std::invalid_argument("resample_on_x_grid: non-finite point " + std::to_string(i));
    }
    if (!(b.x_m > reach_m)) continue;
    // a.x <= reach < b.x, so the segment rises in x and every new grid x lies on it.
    const Point& a = normalized[i - 1];
    const double inv_dx = 1.0 / (b.x_m - a.x_m);
    while (k < n && grid_x(k) <= b.x_m + tol_m) {
      const double f = std::min(1.0, (grid_x(k) - a.x_m) * inv_dx);
      y_out[k++] = a.y_m + f * (b.y_m - a.y_m);
    }
    reach_m = b.x_m;
  }
  if (k == n) return;
  if (!goal_ray_extends_in_x(goal_dheading_deg)) {
    y_out.resize(k);
    return;
  }
  // The ray x = last.x + s sin g, y = last.y + s cos g, as y(x). Unfilled grid x exceed reach,
  // which is at least last.x, so they lie ahead of the last point.
  const double g_rad = deg_to_rad(std::abs(goal_dheading_deg));
  const double dy_per_dx = std::cos(g_rad) / std::sin(g_rad);
  const Point& last = normalized.back();
  for (; k < n; ++k)
    y_out[k] = last.y_m + (grid_x(k) - last.x_m) * dy_per_dx;
}

XGridCurve resample_on_x_grid(const Polyline& normalized, double goal_dheading_deg, double x_max_m,
                              double step_m) {
  XGridCurve c;
  c.x0_m = 0.0;
  c.step_m = step_m;
  resample_on_x_grid_into(normalized, goal_dheading_deg, x_max_m, step_m, c.y_m);
  return c;
}

XGridCurve mean_turn(const std::vector<Polyline>& normalized_turns, double goal_dheading_deg,
                     const MeanTurnOptions& options) {
  if (normalized_turns.empty()) throw std::invalid_argument("mean turn: no turns given");
  for (std::size_t i = 0; i < normalized_turns.size(); ++i)
    check_turn(normalized_turns[i], "mean turn", i);
  const double x_max = set_x_max_m(normalized_turns, goal_dheading_deg, options.x_margin_m);

  XGridCurve mean;
  mean.x0_m = 0.0;
  mean.step_m = options.x_step_m;
  mean.y_m.assign(x_grid_size(x_max, options.x_step_m), 0.0);
  std::size_t common = mean.y_m.size();
  std::vector<double> y;
  for (const auto& turn : normalized_turns) {
    resample_on_x_grid_into(turn, goal_dheading_deg, x_max, options.x_step_m, y);
    // Only a non-extending goal can leave a curve short; the average is then over the part every
    // turn covers.
    common = std::min(common, y.size());
    for (std::size_t k = 0; k < common; ++k)
      mean.y_m[k] += y[k];
  }
  mean.y_m.resize(common);
  const double inv_n = 1.0 / static_cast<double>(normalized_turns.size());
  for (double& v : mean.y_m)
    v *= inv_n;
  return mean;
}

}  // namespace avk::kinematics
