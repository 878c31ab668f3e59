#include "kinematics/retimed_turn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "kinematics/turn_measures.hpp"

namespace avk::kinematics {

namespace {

// The integral of u(t) / u0 over [a, b] (trapezoids no longer than 0.05 s).
double speed_ratio_integral(const SpeedResponse& r, double u0, double u1, double a, double b) {
  if (!(b > a)) return 0.0;
  const int n = std::max(1, static_cast<int>(std::ceil((b - a) / 0.05)));
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    sum += w * r.speed_at_mps(a + i * h, u0, u1) / u0;
  }
  return sum * h;
}

}  // namespace

RetimedTurn retime_turn(const Polyline& trajectory, const std::optional<TurnTiming>& timing,
                        double u0_mps, double u1_mps, const SpeedResponse& response) {
  if (!(u0_mps > 0.0) || !(u1_mps > 0.0) || !std::isfinite(u0_mps) || !std::isfinite(u1_mps))
    throw std::invalid_argument("speeds before and after the change must be positive");
  if (trajectory.size() < 2) throw std::invalid_argument("the turn needs at least 2 points");
  const std::vector<double> s = cumulative_arc_length_m(trajectory);
  const TurnTiming base = timing ? *timing : constant_speed_timing(s.back(), u0_mps);
  RetimedTurn out;
  out.trajectory.reserve(trajectory.size());
  out.time_s.reserve(trajectory.size());
  Point p = trajectory.front();
  out.trajectory.push_back(p);
  double t_prev = time_at_length_s(base, 0.0, u0_mps);
  out.time_s.push_back(t_prev);
  std::vector<double> new_s{0.0};
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double ds = s[i] - s[i - 1];
    const double t = std::max(t_prev, time_at_length_s(base, s[i], u0_mps));
    double new_ds = 0.0;
    if (ds > 0.0) {
      // The segment's own speed ds / dt, scaled by u(t) / u0 over its interval.
      new_ds = t > t_prev
                   ? ds / (t - t_prev) * speed_ratio_integral(response, u0_mps, u1_mps, t_prev, t)
                   : ds * response.speed_at_mps(t, u0_mps, u1_mps) / u0_mps;
      const Point a = trajectory[i - 1], b = trajectory[i];
      p = {p.x_m + (b.x_m - a.x_m) / ds * new_ds, p.y_m + (b.y_m - a.y_m) / ds * new_ds};
    }
    out.trajectory.push_back(p);
    out.time_s.push_back(t);
    new_s.push_back(new_s.back() + new_ds);
    t_prev = t;
  }
  // The times at equal fractions of the new length.
  out.timing.length_m = new_s.back();
  out.timing.time_s.resize(kTimingStations);
  std::size_t j = 0;
  for (std::size_t k = 0; k < kTimingStations; ++k) {
    const double l =
        out.timing.length_m * static_cast<double>(k) / static_cast<double>(kTimingStations - 1);
    while (j + 2 < new_s.size() && new_s[j + 1] < l)
      ++j;
    const double span = new_s[j + 1] - new_s[j];
    const double w = span > 0.0 ? std::clamp((l - new_s[j]) / span, 0.0, 1.0) : 0.0;
    out.timing.time_s[k] = out.time_s[j] + w * (out.time_s[j + 1] - out.time_s[j]);
  }
  const Point origin = trajectory.front();
  Polyline from_origin = out.trajectory;
  for (Point& q : from_origin)
    q = {q.x_m - origin.x_m, q.y_m - origin.y_m};
  const AdvanceTransfer at = advance_transfer(from_origin);
  out.advance_m = at.advance_m;
  out.transfer_m = at.transfer_m;
  return out;
}

RetimedTurn retime_turn(const TurnPrediction& constant_speed, double u0_mps, double u1_mps,
                        const SpeedResponse& response) {
  RetimedTurn out =
      retime_turn(constant_speed.trajectory, constant_speed.timing, u0_mps, u1_mps, response);
  // The table's advance and transfer are where its turns ended, short of its trajectory's run-on
  // along the goal heading: the same point of the turn, re-timed (the nearest point of the
  // constant-speed trajectory to it, carried to the re-timed one segment by segment).
  const Polyline& base = constant_speed.trajectory;
  const double side = constant_speed.dheading_deg < 0.0 ? -1.0 : 1.0;
  const Point end{side * constant_speed.transfer_m, constant_speed.advance_m};
  double best = std::numeric_limits<double>::infinity();
  Point carried = out.trajectory.back();
  for (std::size_t i = 0; i + 1 < base.size(); ++i) {
    const Point a = base[i], b = base[i + 1];
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m, len2 = dx * dx + dy * dy;
    const double w =
        len2 > 0.0 ? std::clamp(((end.x_m - a.x_m) * dx + (end.y_m - a.y_m) * dy) / len2, 0.0, 1.0)
                   : 0.0;
    const double d = std::hypot(a.x_m + w * dx - end.x_m, a.y_m + w * dy - end.y_m);
    if (d < best) {
      best = d;
      const Point p = out.trajectory[i], q = out.trajectory[i + 1];
      carried = {p.x_m + w * (q.x_m - p.x_m), p.y_m + w * (q.y_m - p.y_m)};
    }
  }
  const Point origin = out.trajectory.front();
  out.advance_m = carried.y_m - origin.y_m;
  out.transfer_m = side * (carried.x_m - origin.x_m);
  return out;
}

}  // namespace avk::kinematics
