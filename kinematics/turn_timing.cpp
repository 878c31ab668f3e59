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
    // At u = 1 the length is the next vertex's exactly, so a path run onto the trajectory's end
    // reaches its full length rather than a rounding short of it.
    if (d < best.distance_m) best = {i, u < 1.0 ? s[i] + u * (s[i + 1] - s[i]) : s[i + 1], d};
  }
  return best;
}

// The time at which a path stationed by time passes each of the kTimingStations stations of the
// trajectory (arc lengths s): its points projected forward onto the trajectory, the lengths made
// non-decreasing, the first time each station is reached, and past the projection of its last
// point the commanded speed. The caller checks the speed and that the path has 2 points.
std::vector<double> times_along(const StationedPath& by_time, double commanded_speed_mps,
                                const Polyline& trajectory, const std::vector<double>& s) {
  const double length = s.back();
  // Projected length and time of each point. The search only moves forward, a few segments at a
  // time, so a path that curls back towards its start (a 180 deg turn) is followed in order
  // rather than snapping to an earlier part that passes close by.
  constexpr std::size_t kWindow = 8;
  std::vector<double> at_length, at_time;
  at_length.reserve(by_time.points.size());
  at_time.reserve(by_time.points.size());
  std::size_t segment = 0;
  double reached = 0.0;
  for (std::size_t k = 0; k < by_time.points.size(); ++k) {
    const Projection p = project_forward(trajectory, s, by_time.points[k], segment, kWindow);
    segment = p.segment;
    reached = std::max(reached, p.length_m);
    at_length.push_back(reached);
    at_time.push_back(by_time.s_m[k] / commanded_speed_mps);
  }
  std::vector<double> time_s(kTimingStations);
  const double end_length = at_length.back(), end_time = at_time.back();
  std::size_t j = 0;
  for (std::size_t i = 0; i < kTimingStations; ++i) {
    const double l = length * static_cast<double>(i) / static_cast<double>(kTimingStations - 1);
    if (l > end_length) {
      // The trajectory's run-on past the path's end: at the commanded speed.
      time_s[i] = end_time + (l - end_length) / commanded_speed_mps;
      continue;
    }
    // The first time the path reached l (lengths are non-decreasing): a path that runs on past
    // the trajectory's end reaches its last station when it first gets there, not when it stops.
    while (j + 1 < at_length.size() && at_length[j + 1] < l)
      ++j;
    const double l0 = at_length[j], l1 = at_length[j + 1];
    const double w = l1 > l0 ? std::clamp((l - l0) / (l1 - l0), 0.0, 1.0) : 0.0;
    time_s[i] = at_time[j] + w * (at_time[j + 1] - at_time[j]);
  }
  time_s[0] = 0.0;
  for (std::size_t i = 1; i < kTimingStations; ++i)
    time_s[i] = std::max(time_s[i], time_s[i - 1]);
  return time_s;
}

// The trajectory's cumulative lengths when it can be timed at this speed: 2 points or more, a
// positive length and a positive finite speed.
std::optional<std::vector<double>> timeable(const Polyline& trajectory,
                                            double commanded_speed_mps) {
  if (trajectory.size() < 2 || !(commanded_speed_mps > 0.0) || !std::isfinite(commanded_speed_mps))
    return std::nullopt;
  std::vector<double> s = cumulative_arc_length_m(trajectory);
  if (!(s.back() > 0.0)) return std::nullopt;
  return s;
}

// The path with points inserted so that consecutive points are at most step_m apart, in station
// and in space: a turn logged at 1 Hz moves metres between fixes, farther than the projection's
// forward window of trajectory segments may reach.
StationedPath densified(const StationedPath& path, double step_m) {
  StationedPath out;
  out.s_m.push_back(path.s_m.front());
  out.points.push_back(path.points.front());
  for (std::size_t k = 1; k < path.points.size(); ++k) {
    const Point a = path.points[k - 1], b = path.points[k];
    const double gap = std::max(path.s_m[k] - path.s_m[k - 1], distance_m(a, b));
    const auto n = static_cast<std::size_t>(std::clamp(std::ceil(gap / step_m), 1.0, 1e6));
    for (std::size_t i = 1; i <= n; ++i) {
      const double u = static_cast<double>(i) / static_cast<double>(n);
      out.s_m.push_back(path.s_m[k - 1] + u * (path.s_m[k] - path.s_m[k - 1]));
      out.points.push_back({a.x_m + u * (b.x_m - a.x_m), a.y_m + u * (b.y_m - a.y_m)});
    }
  }
  return out;
}

// Values at kTimingStations equal fractions of length_m, interpolated at l in (0, length_m).
double at_station_length(const std::vector<double>& v, double length_m, double l_m) {
  const double x = l_m / length_m * static_cast<double>(kTimingStations - 1);
  const auto i = std::min(kTimingStations - 2, static_cast<std::size_t>(x));
  const double w = x - static_cast<double>(i);
  return v[i] + w * (v[i + 1] - v[i]);
}

}  // namespace

std::optional<TurnTiming> timing_of(const StationedPath& mean_by_time, double commanded_speed_mps,
                                    const Polyline& trajectory) {
  const auto s = timeable(trajectory, commanded_speed_mps);
  if (!s || mean_by_time.points.size() < 2) return std::nullopt;
  TurnTiming t;
  t.length_m = s->back();
  t.time_s = times_along(mean_by_time, commanded_speed_mps, trajectory, *s);
  return t;
}

std::vector<double> timing_spread_s(const std::vector<StationedPath>& turns_by_time,
                                    double commanded_speed_mps, const Polyline& trajectory) {
  const auto s = timeable(trajectory, commanded_speed_mps);
  if (!s) return {};
  std::vector<std::vector<double>> times;
  for (const StationedPath& turn : turns_by_time) {
    if (turn.points.size() < 2 || turn.s_m.size() != turn.points.size()) continue;
    times.push_back(
        times_along(densified(turn, kStationStep_m), commanded_speed_mps, trajectory, *s));
  }
  if (times.size() < 2) return {};
  const auto n = static_cast<double>(times.size());
  std::vector<double> sd(kTimingStations);
  for (std::size_t i = 0; i < kTimingStations; ++i) {
    double mean = 0.0;
    for (const auto& t : times)
      mean += t[i] / n;
    double ss = 0.0;
    for (const auto& t : times)
      ss += (t[i] - mean) * (t[i] - mean);
    sd[i] = std::sqrt(ss / (n - 1.0));
  }
  return sd;
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

double time_sd_at_length_s(const TurnTiming& timing, double l_m) {
  const std::vector<double>& sd = timing.time_sd_s;
  if (sd.size() != kTimingStations) return 0.0;
  if (l_m <= 0.0) return sd.front();
  if (l_m >= timing.length_m) return sd.back();
  return at_station_length(sd, timing.length_m, l_m);
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
  return at_station_length(timing.time_s, timing.length_m, l_m);
}

std::optional<TurnTiming> blend_timings(
    const std::vector<std::pair<const std::optional<TurnTiming>*, double>>& sources) {
  if (sources.empty()) return std::nullopt;
  TurnTiming out;
  out.time_s.assign(kTimingStations, 0.0);
  bool spread = true;
  for (const auto& [t, w] : sources)
    spread = spread && t && *t && (*t)->time_sd_s.size() == kTimingStations;
  if (spread) out.time_sd_s.assign(kTimingStations, 0.0);
  for (const auto& [t, w] : sources) {
    if (!t || !*t || (*t)->time_s.size() != kTimingStations) return std::nullopt;
    out.length_m += w * (*t)->length_m;
    for (std::size_t k = 0; k < kTimingStations; ++k)
      out.time_s[k] += w * (*t)->time_s[k];
    if (spread) {
      for (std::size_t k = 0; k < kTimingStations; ++k)
        out.time_sd_s[k] += w * (*t)->time_sd_s[k];
    }
  }
  return out;
}

TurnTiming scaled_timing(const TurnTiming& timing, double new_length_m) {
  TurnTiming out = timing;
  const double r = timing.length_m > 0.0 ? new_length_m / timing.length_m : 1.0;
  out.length_m = new_length_m;
  for (double& t : out.time_s)
    t *= r;
  for (double& sd : out.time_sd_s)
    sd *= r;
  return out;
}

}  // namespace avk::kinematics
