#include "kinematics/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

double distance_m(Point a, Point b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

double distance_to_segment_m(Point p, Point a, Point b) {
  const double dx = b.x_m - a.x_m;
  const double dy = b.y_m - a.y_m;
  const double len2 = dx * dx + dy * dy;
  if (len2 == 0.0) return distance_m(p, a);
  double t = ((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / len2;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x_m - (a.x_m + t * dx), p.y_m - (a.y_m + t * dy));
}

double distance_to_polyline_m(Point p, const Polyline& line) {
  if (line.empty()) return std::numeric_limits<double>::infinity();
  if (line.size() == 1) return distance_m(p, line.front());
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < line.size(); ++i) {
    best = std::min(best, distance_to_segment_m(p, line[i - 1], line[i]));
  }
  return best;
}

std::vector<double> cumulative_arc_length_m(const Polyline& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i)
    s[i] = s[i - 1] + distance_m(line[i - 1], line[i]);
  return s;
}

double arc_length_m(const Polyline& line) {
  double s = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i)
    s += distance_m(line[i - 1], line[i]);
  return s;
}

Polyline resample_by_arc_length(const Polyline& line, double step_m) {
  if (line.size() < 2 || !(step_m > 0.0)) return line;
  const std::vector<double> s = cumulative_arc_length_m(line);
  const double total = s.back();
  const auto n = static_cast<std::size_t>(std::ceil(total / step_m));
  Polyline out;
  out.reserve(n + 1);
  std::size_t seg = 1;
  for (std::size_t k = 0; k <= n; ++k) {
    const double target = std::min(total, static_cast<double>(k) * step_m);
    while (seg + 1 < s.size() && s[seg] < target)
      ++seg;
    const double len = s[seg] - s[seg - 1];
    const double t = len > 0.0 ? (target - s[seg - 1]) / len : 0.0;
    out.push_back({line[seg - 1].x_m + t * (line[seg].x_m - line[seg - 1].x_m),
                   line[seg - 1].y_m + t * (line[seg].y_m - line[seg - 1].y_m)});
  }
  return out;
}

Point rotate_by_heading(Point v, double dheading_deg) {
  // A heading angle grows clockwise, so this is a mathematical rotation by -dheading.
  const double c = std::cos(deg_to_rad(dheading_deg));
  const double s = std::sin(deg_to_rad(dheading_deg));
  return {v.x_m * c + v.y_m * s, -v.x_m * s + v.y_m * c};
}

Polyline reflect_x(Polyline line) {
  for (Point& p : line)
    p.x_m = 0.0 - p.x_m;  // not -x: keeps the lead-in at +0, not -0
  return line;
}

Polyline place_normalized(const Polyline& normalized, const Pose& pose, TurnSide side) {
  Polyline out;
  out.reserve(normalized.size());
  const double mirror = side == TurnSide::left ? -1.0 : 1.0;
  for (const Point& p : normalized) {
    const Point r = rotate_by_heading({mirror * p.x_m, p.y_m}, pose.heading_deg);
    out.push_back({pose.x_m + r.x_m, pose.y_m + r.y_m});
  }
  return out;
}

Point normalize_point(Point world, const Pose& start, TurnSide side) {
  const Point r =
      rotate_by_heading({world.x_m - start.x_m, world.y_m - start.y_m}, -start.heading_deg);
  return {side == TurnSide::left ? -r.x_m : r.x_m, r.y_m};
}

}  // namespace avk::kinematics
