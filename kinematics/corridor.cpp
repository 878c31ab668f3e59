#include "kinematics/corridor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/students_t.hpp>

namespace avk::kinematics {

namespace {

Point unit(Point v) {
  const double n = std::hypot(v.x_m, v.y_m);
  return n > 0.0 ? Point{v.x_m / n, v.y_m / n} : Point{0.0, 1.0};
}

// Direction of travel at station s, by a central difference over a short span.
Point direction_at(const StationedPath& path, double s_m, double goal_dheading_deg) {
  const double h = 0.5 * kStationStep_m;
  const Point a = point_at_station(path, std::max(0.0, s_m - h), goal_dheading_deg);
  const Point b = point_at_station(path, s_m + h, goal_dheading_deg);
  return unit({b.x_m - a.x_m, b.y_m - a.y_m});
}

}  // namespace

std::optional<Corridor> corridor_of(const std::vector<StationedPath>& turns,
                                    const StationedPath& mean, double goal_dheading_deg) {
  if (turns.size() < 2) return std::nullopt;
  Corridor c;
  c.n_turns = turns.size();
  c.length_m = longest_m(turns);
  c.lateral_sd_m.resize(kCorridorStations);
  const double n = static_cast<double>(turns.size());
  for (std::size_t k = 0; k < kCorridorStations; ++k) {
    const double s = c.length_m * static_cast<double>(k) / (kCorridorStations - 1);
    double sum = 0.0, sum2 = 0.0;
    for (const auto& t : turns) {
      const double e =
          lateral_offset_m(mean, s, point_at_station(t, s, goal_dheading_deg), goal_dheading_deg);
      sum += e;
      sum2 += e * e;
    }
    const double m = sum / n;
    c.lateral_sd_m[k] = std::sqrt(std::max(0.0, (sum2 - n * m * m) / (n - 1.0)));
  }
  return c;
}

double lateral_sd_at_m(const Corridor& c, double s_m) {
  if (c.lateral_sd_m.empty()) return 0.0;
  if (!(c.length_m > 0.0) || s_m <= 0.0) return c.lateral_sd_m.front();
  const double f = s_m / c.length_m * static_cast<double>(c.lateral_sd_m.size() - 1);
  if (f >= static_cast<double>(c.lateral_sd_m.size() - 1)) return c.lateral_sd_m.back();
  const auto i = static_cast<std::size_t>(f);
  const double w = f - static_cast<double>(i);
  return (1.0 - w) * c.lateral_sd_m[i] + w * c.lateral_sd_m[i + 1];
}

double corridor_factor(std::size_t n_turns, double share) {
  if (n_turns < 2) throw std::invalid_argument("a corridor needs at least 2 turns");
  if (!(share > 0.0 && share < 1.0))
    throw std::invalid_argument("a corridor's share must be within (0, 1)");
  const double n = static_cast<double>(n_turns);
  const boost::math::students_t dist(n - 1.0);
  return boost::math::quantile(dist, 0.5 * (1.0 + share)) * std::sqrt(1.0 + 1.0 / n);
}

std::optional<Corridor> blend_corridors(
    const std::vector<std::pair<const std::optional<Corridor>*, double>>& sources) {
  if (sources.empty()) return std::nullopt;
  Corridor out;
  out.lateral_sd_m.assign(kCorridorStations, 0.0);
  out.n_turns = static_cast<std::size_t>(-1);
  for (const auto& [c, w] : sources) {
    if (!c || !*c || (*c)->lateral_sd_m.size() != kCorridorStations) return std::nullopt;
    out.n_turns = std::min(out.n_turns, (*c)->n_turns);
    out.length_m += w * (*c)->length_m;
    for (std::size_t k = 0; k < kCorridorStations; ++k)
      out.lateral_sd_m[k] += w * (*c)->lateral_sd_m[k];
  }
  return out;
}

double lateral_offset_m(const StationedPath& path, double s_m, Point q, double goal_dheading_deg) {
  const Point p = point_at_station(path, s_m, goal_dheading_deg);
  const Point t = direction_at(path, s_m, goal_dheading_deg);
  // Right of the direction of travel: the tangent turned 90° clockwise.
  return (q.x_m - p.x_m) * t.y_m - (q.y_m - p.y_m) * t.x_m;
}

std::vector<double> corridor_half_widths_m(const Polyline& trajectory, const Corridor& c,
                                           double share) {
  const double factor = corridor_factor(c.n_turns, share);
  const std::vector<double> s = cumulative_arc_length_m(trajectory);
  const double length = s.empty() ? 0.0 : s.back();
  // The corridor's stations were measured on the mean path; the trajectory (a fit of it, or a
  // blend of cells) is a little shorter or longer, so stations map by fraction of length.
  const double to_corridor = length > 0.0 ? c.length_m / length : 0.0;
  std::vector<double> w(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    w[i] = factor * lateral_sd_at_m(c, s[i] * to_corridor);
  return w;
}

CorridorBand corridor_band(const Polyline& trajectory, const Corridor& c, double share) {
  CorridorBand b;
  b.share = share;
  b.n_turns = c.n_turns;
  b.s_m = cumulative_arc_length_m(trajectory);
  b.half_width_m = corridor_half_widths_m(trajectory, c, share);
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const Point a = trajectory[i > 0 ? i - 1 : i];
    const Point z = trajectory[i + 1 < trajectory.size() ? i + 1 : i];
    const Point t = unit({z.x_m - a.x_m, z.y_m - a.y_m});
    const Point right{t.y_m, -t.x_m};
    const double w = b.half_width_m[i];
    b.left.push_back({trajectory[i].x_m - w * right.x_m, trajectory[i].y_m - w * right.y_m});
    b.right.push_back({trajectory[i].x_m + w * right.x_m, trajectory[i].y_m + w * right.y_m});
  }
  return b;
}

Coverage corridor_coverage(const StationedPath& held_out, const StationedPath& mean,
                           const Corridor& c, double goal_dheading_deg, double share,
                           double step_m) {
  Coverage cov;
  const double factor = corridor_factor(c.n_turns, share);
  const double span = held_out.length_m();
  // Station 0 is left out: every turn starts at the origin, so it would count as inside for free.
  const auto n = static_cast<std::size_t>(std::floor(span / step_m + 1e-9));
  for (std::size_t k = 1; k <= n; ++k) {
    const double s = static_cast<double>(k) * step_m;
    const double e = lateral_offset_m(mean, s, point_at_station(held_out, s, goal_dheading_deg),
                                      goal_dheading_deg);
    ++cov.total;
    if (std::abs(e) <= factor * lateral_sd_at_m(c, s)) ++cov.inside;
  }
  return cov;
}

}  // namespace avk::kinematics
