#include "kinematics/turn_timing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace avk::kinematics {

namespace {

struct Projection {
  std::size_t segment = 0;
  double length_m = 0.0;  // along the trajectory
  double distance_m = std::numeric_limits<double>::infinity();
};

// The nearest point of segments [from, from + window) of the trajectory to p.
Projection project_forward(const Polyline& line, const std::vector<double>& s, Point p,
                           std::size_t from, std::size_t window) {
  Projection best;
  const std::size_t end = std::min(line.size() - 1, from + window);
  for (std::size_t i = from; i < end; ++i) {
    const Point a = line[i], b = line[i + 1];
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
    const double len2 = dx * dx + dy * dy;
    const double u =
        len2 > 0.0 ? std::clamp(((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / len2, 0.0, 1.0)
                   : 0.0;
    const double d = std::hypot(a.x_m + u * dx - p.x_m, a.y_m + u * dy - p.y_m);
    if (d < best.distance_m) best = {i, s[i] + u * (s[i + 1] - s[i]), d};
  }
  return best;
}

}  // namespace

std::optional<TurnTiming> timing_of(const StationedPath& mean_by_time, double commanded_speed_mps,
                                    const Polyline& trajectory) {
  if (trajectory.size() < 2 || mean_by_time.points.size() < 2 || !(commanded_speed_mps > 0.0) ||
      !std::isfinite(commanded_speed_mps))
    return std::nullopt;
  const std::vector<double> s = cumulative_arc_length_m(trajectory);
  const double length = s.back();
  if (!(length > 0.0)) return std::nullopt;
  // Projected length and time of each mean point. The search only moves forward, a few segments
  // at a time, so a path that curls back towards its start (a 180 deg turn) is followed in order
  // rather than snapping to an earlier part that passes close by.
  constexpr std::size_t kWindow = 8;
  std::vector<double> at_length, at_time;
  at_length.reserve(mean_by_time.points.size());
  at_time.reserve(mean_by_time.points.size());
  std::size_t segment = 0;
  double reached = 0.0;
  for (std::size_t k = 0; k < mean_by_time.points.size(); ++k) {
    const Projection p = project_forward(trajectory, s, mean_by_time.points[k], segment, kWindow);
    segment = p.segment;
    reached = std::max(reached, p.length_m);
    at_length.push_back(reached);
    at_time.push_back(mean_by_time.s_m[k] / commanded_speed_mps);
  }
  TurnTiming t;
  t.length_m = length;
  t.time_s.resize(kTimingStations);
  const double end_length = at_length.back(), end_time = at_time.back();
  std::size_t j = 0;
  for (std::size_t i = 0; i < kTimingStations; ++i) {
    const double l = length * static_cast<double>(i) / static_cast<double>(kTimingStations - 1);
    if (l >= end_length) {
      // The trajectory's run-on past the longest turn: at the commanded speed.
      t.time_s[i] = end_time + (l - end_length) / commanded_speed_mps;
      continue;
    }
    // The first time the mean reached l (lengths are non-decreasing).
    while (j + 1 < at_length.size() && at_length[j + 1] < l)
      ++j;
    const double l0 = at_length[j], l1 = at_length[j + 1];
    const double w = l1 > l0 ? std::clamp((l - l0) / (l1 - l0), 0.0, 1.0) : 0.0;
    t.time_s[i] = at_time[j] + w * (at_time[j + 1] - at_time[j]);
  }
  t.time_s[0] = 0.0;
  for (std::size_t i = 1; i < kTimingStations; ++i)
    t.time_s[i] = std::max(t.time_s[i], t.time_s[i - 1]);
  return t;
}

TurnTiming constant_speed_timing(double length_m, double speed_mps) {
  if (!(speed_mps > 0.0) || !(length_m >= 0.0))
    throw std::invalid_argument("a constant-speed timing needs a positive speed and a length");
  TurnTiming t;
  t.length_m = length_m;
  t.time_s.resize(kTimingStations);
  for (std::size_t i = 0; i < kTimingStations; ++i)
    t.time_s[i] =
        length_m * static_cast<double>(i) / static_cast<double>(kTimingStations - 1) / speed_mps;
  return t;
}

double time_at_length_s(const TurnTiming& timing, double l_m, double end_speed_mps) {
  if (timing.time_s.size() != kTimingStations)
    throw std::invalid_argument("a timing needs " + std::to_string(kTimingStations) + " stations");
  if (l_m <= 0.0) return 0.0;
  if (l_m >= timing.length_m) {
    if (l_m == timing.length_m) return timing.time_s.back();
    if (!(end_speed_mps > 0.0))
      throw std::invalid_argument("past the end of a timing the speed must be positive");
    return timing.time_s.back() + (l_m - timing.length_m) / end_speed_mps;
  }
  const double x = l_m / timing.length_m * static_cast<double>(kTimingStations - 1);
  const auto i = std::min(kTimingStations - 2, static_cast<std::size_t>(x));
  const double w = x - static_cast<double>(i);
  return timing.time_s[i] + w * (timing.time_s[i + 1] - timing.time_s[i]);
}

std::optional<TurnTiming> blend_timings(
    const std::vector<std::pair<const std::optional<TurnTiming>*, double>>& sources) {
  if (sources.empty()) return std::nullopt;
  TurnTiming out;
  out.time_s.assign(kTimingStations, 0.0);
  for (const auto& [t, w] : sources) {
    if (!t || !*t || (*t)->time_s.size() != kTimingStations) return std::nullopt;
    out.length_m += w * (*t)->length_m;
    for (std::size_t k = 0; k < kTimingStations; ++k)
      out.time_s[k] += w * (*t)->time_s[k];
  }
  return out;
}

TurnTiming scaled_timing(const TurnTiming& timing, double new_length_m) {
  TurnTiming out = timing;
  const double r = timing.length_m > 0.0 ? new_length_m / timing.length_m : 1.0;
  out.length_m = new_length_m;
  for (double& t : out.time_s)
    t *= r;
  return out;
}

}  // namespace avk::kinematics
