#include "kinematics/path_metric.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"
#include "kinematics/mean_turn.hpp"

namespace avk::kinematics {

namespace {

Point goal_direction(double goal_dheading_deg) {
  const double g = deg_to_rad(std::abs(goal_dheading_deg));
  return {std::sin(g), std::cos(g)};
}

std::size_t station_count(double s_max_m, double step_m) {
  if (!(step_m > 0.0) || !std::isfinite(step_m))
    throw std::invalid_argument("station step must be finite and > 0");
  if (!std::isfinite(s_max_m) || s_max_m < 0.0)
    throw std::invalid_argument("station span must be finite and >= 0");
  const double n = std::floor(s_max_m / step_m + 1e-9);
  if (n + 1.0 > static_cast<double>(kMaxXGridPoints))
    throw std::invalid_argument("station grid longer than " + std::to_string(kMaxXGridPoints) +
                                " points");
  return static_cast<std::size_t>(n) + 1;
}

}  // namespace

StationedPath stationed_by_time(const TurnSequence& turn) {
  const TurnSequence norm = turn.meta().normalized ? turn : turn.normalized();
  const double u = norm.meta().commanded_speed_mps;
  if (!(u > 0.0) || !std::isfinite(u))
    throw std::invalid_argument("a turn stationed by time needs a commanded speed > 0");
  const auto& samples = norm.samples();
  if (samples.empty()) throw std::invalid_argument("a turn without samples has no path");
  StationedPath p;
  p.s_m.reserve(samples.size());
  p.points.reserve(samples.size());
  const double t0 = samples.front().t_s;
  for (const auto& s : samples) {
    p.s_m.push_back(u * (s.t_s - t0));
    p.points.push_back({s.x_m, s.y_m});
  }
  return p;
}

StationedPath stationed_by_length(const Polyline& path) {
  if (path.empty()) throw std::invalid_argument("an empty path has no stations");
  return {cumulative_arc_length_m(path), path};
}

Point point_at_station(const StationedPath& path, double s_m, double goal_dheading_deg) {
  if (path.points.empty()) throw std::invalid_argument("an empty path has no stations");
  const auto& s = path.s_m;
  if (s_m <= s.front()) return path.points.front();
  if (s_m >= s.back()) {
    const Point d = goal_direction(goal_dheading_deg);
    const Point last = path.points.back();
    const double ds = s_m - s.back();
    return {last.x_m + ds * d.x_m, last.y_m + ds * d.y_m};
  }
  const auto hi = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), s_m) - s.begin());
  const std::size_t lo = hi - 1;
  const double span = s[hi] - s[lo];
  const double w = span > 0.0 ? (s_m - s[lo]) / span : 0.0;
  const Point a = path.points[lo], b = path.points[hi];
  return {a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m)};
}

Polyline points_at_stations(const StationedPath& path, double goal_dheading_deg, double s_max_m,
                            double step_m) {
  const std::size_t n = station_count(s_max_m, step_m);
  Polyline out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k)
    out.push_back(point_at_station(path, static_cast<double>(k) * step_m, goal_dheading_deg));
  return out;
}

double mean_path_distance_m(const StationedPath& a, const StationedPath& b,
                            double goal_dheading_deg, double s_max_m, double step_m) {
  const std::size_t n = station_count(s_max_m, step_m);
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) * step_m;
    sum += distance_m(point_at_station(a, s, goal_dheading_deg),
                      point_at_station(b, s, goal_dheading_deg));
  }
  return sum / static_cast<double>(n);
}

StationedPath instantaneous_path() {
  // One point: every station past 0 lies on the goal ray from the origin.
  return {{0.0}, {{0.0, 0.0}}};
}

double longest_m(const std::vector<StationedPath>& paths) {
  double longest = 0.0;
  for (const auto& p : paths)
    longest = std::max(longest, p.length_m());
  return longest;
}

StationedPath mean_path_at_stations(const std::vector<StationedPath>& paths,
                                    double goal_dheading_deg, double step_m) {
  if (paths.empty()) throw std::invalid_argument("the mean of no paths");
  const double s_max = longest_m(paths);
  const std::size_t n = station_count(s_max, step_m);
  StationedPath mean;
  mean.s_m.resize(n);
  mean.points.assign(n, Point{});
  const double w = 1.0 / static_cast<double>(paths.size());
  for (const auto& p : paths) {
    if (p.points.empty()) throw std::invalid_argument("the mean of paths: an empty path");
    for (std::size_t k = 0; k < n; ++k) {
      const Point q = point_at_station(p, static_cast<double>(k) * step_m, goal_dheading_deg);
      mean.points[k].x_m += w * q.x_m;
      mean.points[k].y_m += w * q.y_m;
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    mean.s_m[k] = static_cast<double>(k) * step_m;
  return mean;
}

}  // namespace avk::kinematics
