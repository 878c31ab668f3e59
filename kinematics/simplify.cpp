#include "kinematics/simplify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace avk::kinematics {

namespace {

// Squared distance from p to segment ab times |ab|^2: within one segment only the order of the
// distances matters, and the scaling keeps the division out of DP's inner loop.
double scaled_squared_distance(Point p, Point a, double dx, double dy, double len2) {
  const double px = p.x_m - a.x_m;
  const double py = p.y_m - a.y_m;
  const double along = px * dx + py * dy;
  if (along <= 0.0) return (px * px + py * py) * len2;
  if (along >= len2) {
    const double qx = px - dx;
    const double qy = py - dy;
    return (qx * qx + qy * qy) * len2;
  }
  const double cross = px * dy - py * dx;
  return cross * cross;
}

}  // namespace

Polyline simplify_polyline(const Polyline& dense, double epsilon_m) {
  if (!(epsilon_m >= 0.0)) throw std::invalid_argument("simplify_polyline: epsilon_m must be >= 0");
  const std::size_t n = dense.size();
  if (n <= 2) return dense;
  const double eps2 = epsilon_m * epsilon_m;
  std::vector<char> keep(n, 0);
  keep.front() = 1;
  keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  stack.reserve(64);
  stack.emplace_back(0, n - 1);
  std::size_t kept = 2;
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    const Point a = dense[first];
    const double dx = dense[last].x_m - a.x_m;
    const double dy = dense[last].y_m - a.y_m;
    // A closed stretch (both ends equal) measures plain distances from that point.
    const double len2 = dx * dx + dy * dy > 0.0 ? dx * dx + dy * dy : 1.0;
    double worst = -1.0;
    std::size_t worst_index = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const double d2 = scaled_squared_distance(dense[i], a, dx, dy, len2);
      if (d2 > worst) {
        worst = d2;
        worst_index = i;
      }
    }
    if (worst > eps2 * len2) {
      keep[worst_index] = 1;
      ++kept;
      if (worst_index - first > 1) stack.emplace_back(first, worst_index);
      if (last - worst_index > 1) stack.emplace_back(worst_index, last);
    }
  }
  Polyline out;
  out.reserve(kept);
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(dense[i]);
  return out;
}

Polyline piecewise_linear(const CurveFit& fit, double epsilon_m) {
  if (!(epsilon_m > 0.0)) throw std::invalid_argument("piecewise_linear: epsilon_m must be > 0");
  // Every curve point is within chord_error of a dense chord, and each dense chord lies within
  // epsilon - chord_error of the simplified polyline (distance to a segment is convex and both
  // chord ends are within it), so the curve is within epsilon. A small share for chord_error
  // costs only a few more dense samples; DP then works with almost all of epsilon.
  const double chord_error_m = epsilon_m / 8.0;
  const Polyline dense = fit.sample(std::numeric_limits<double>::infinity(), chord_error_m);
  return simplify_polyline(dense, epsilon_m - chord_error_m);
}

double max_deviation_m(const Polyline& reference, const Polyline& approx) {
  double worst = 0.0;
  for (const Point& p : reference)
    worst = std::max(worst, distance_to_polyline_m(p, approx));
  return worst;
}

}  // namespace avk::kinematics
