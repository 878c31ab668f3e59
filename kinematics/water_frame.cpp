#include "kinematics/water_frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

TurnSequence in_water_frame(const TurnSequence& raw, WaterCurrent c) {
  if (raw.meta().normalized)
    throw std::invalid_argument("a turn is moved into the water frame before it is normalised");
  if (raw.meta().removed_current)
    throw std::invalid_argument("the turn is already in the water frame");
  if (!std::isfinite(c.east_mps) || !std::isfinite(c.north_mps))
    throw std::invalid_argument("the current must be finite");
  std::vector<TurnSample> samples = raw.samples();
  const double t0 = samples.empty() ? 0.0 : samples.front().t_s;
  for (TurnSample& s : samples) {
    const double dt = s.t_s - t0;
    s.x_m -= c.east_mps * dt;
    s.y_m -= c.north_mps * dt;
    const double h = deg_to_rad(s.heading_deg);
    s.speed_mps -= c.east_mps * std::sin(h) + c.north_mps * std::cos(h);
  }
  TurnMeta meta = raw.meta();
  meta.removed_current = c;
  TurnSequence out(std::move(meta), std::move(samples));
  for (const auto& w : raw.warnings())
    out.add_warning(w);
  if (!out.samples().empty()) out.meta().initial_speed_mps = out.samples().front().speed_mps;
  return out;
}

Point current_in_normalized_frame(WaterCurrent c, double initial_heading_deg, TurnSide side) {
  return normalize_point({c.east_mps, c.north_mps}, Pose{0.0, 0.0, initial_heading_deg}, side);
}

TimedPath drifted(TimedPath path, Point velocity_mps) {
  for (TimedPoint& p : path) {
    p.x_m += velocity_mps.x_m * p.t_s;
    p.y_m += velocity_mps.y_m * p.t_s;
  }
  return path;
}

double over_ground_scale(Point u, Point c) {
  const double uu = u.x_m * u.x_m + u.y_m * u.y_m;
  if (!(uu > 0.0)) return 1.0;
  const double uc = u.x_m * c.x_m + u.y_m * c.y_m;
  const double cc = c.x_m * c.x_m + c.y_m * c.y_m;
  // k² uu + 2k uc + cc − uu = 0
  const double disc = uc * uc - uu * (cc - uu);
  // Without a root the cross current alone is faster than the speed: the best the loop can do
  // is the k that brings the speed over ground nearest, −uc/uu.
  const double k = disc >= 0.0 ? (-uc + std::sqrt(disc)) / uu : -uc / uu;
  return std::clamp(k, kMinOverGroundScale, kMaxOverGroundScale);
}

TimedPath retimed_over_ground(const TimedPath& water_path, Point c) {
  TimedPath out;
  out.reserve(water_path.size());
  if (water_path.empty()) return out;
  out.push_back(water_path.front());
  double t = water_path.front().t_s;
  double x = water_path.front().x_m, y = water_path.front().y_m;
  for (std::size_t i = 1; i < water_path.size(); ++i) {
    const TimedPoint& a = water_path[i - 1];
    const TimedPoint& b = water_path[i];
    const double dt = b.t_s - a.t_s;
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
    // A segment at rest (or without time) is not re-timed: the vehicle waits there as long.
    const double k = dt > 0.0 ? over_ground_scale({dx / dt, dy / dt}, c) : 1.0;
    const double dt_ground = dt / k;
    t += dt_ground;
    x += dx + c.x_m * dt_ground;
    y += dy + c.y_m * dt_ground;
    out.push_back({t, x, y});
  }
  return out;
}

Polyline drifted_trajectory(const Polyline& trajectory, const std::optional<TurnTiming>& timing,
                            double speed_mps, Point velocity_mps) {
  if (!(speed_mps > 0.0)) throw std::invalid_argument("drifted_trajectory: speed must be > 0");
  Polyline out;
  out.reserve(trajectory.size());
  for (const TimedPoint& p :
       drifted(timed_maneuver(0.0, speed_mps, trajectory, timing).path, velocity_mps))
    out.push_back({p.x_m, p.y_m});
  return out;
}

StationedPath stationed_by_clock(const TimedPath& path, double speed_mps) {
  if (path.empty()) throw std::invalid_argument("stationed_by_clock: empty path");
  if (!(speed_mps > 0.0)) throw std::invalid_argument("stationed_by_clock: speed must be > 0");
  StationedPath out;
  out.s_m.reserve(path.size());
  out.points.reserve(path.size());
  const double t0 = path.front().t_s;
  for (const TimedPoint& p : path) {
    out.s_m.push_back(speed_mps * (p.t_s - t0));
    out.points.push_back({p.x_m, p.y_m});
  }
  return out;
}

}  // namespace avk::kinematics
