#include "kinematics/path_approach.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avk::kinematics {

namespace {

// A value given per path point, at time t (linear in between, held at the ends).
double value_at(const TimedPath& path, const std::vector<double>& v, double t_s) {
  if (v.empty()) return 0.0;
  if (t_s <= path.front().t_s) return v.front();
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (path[i].t_s < t_s) continue;
    const double dt = path[i].t_s - path[i - 1].t_s;
    const double w = dt > 0.0 ? (t_s - path[i - 1].t_s) / dt : 1.0;
    return v[i - 1] + w * (v[i] - v[i - 1]);
  }
  return v.back();
}

void check(const TimedPath& p, const std::vector<double>& half_width_m, const char* name) {
  if (p.empty()) throw std::invalid_argument(std::string("path ") + name + " is empty");
  if (!half_width_m.empty() && half_width_m.size() != p.size())
    throw std::invalid_argument(std::string("path ") + name +
                                "'s half widths do not match its points");
}

}  // namespace

TimedPoint position_at(const TimedPath& path, double t_s) {
  if (path.empty()) throw std::invalid_argument("an empty path has no position");
  if (t_s <= path.front().t_s) return {t_s, path.front().x_m, path.front().y_m};
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (path[i].t_s < t_s) continue;
    const TimedPoint& a = path[i - 1];
    const TimedPoint& b = path[i];
    const double dt = b.t_s - a.t_s;
    const double w = dt > 0.0 ? (t_s - a.t_s) / dt : 1.0;
    return {t_s, a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m)};
  }
  return {t_s, path.back().x_m, path.back().y_m};
}

Approach closest_approach(const TimedPath& a, const TimedPath& b,
                          const std::vector<double>& a_half_width_m,
                          const std::vector<double>& b_half_width_m) {
  check(a, a_half_width_m, "a");
  check(b, b_half_width_m, "b");
  const double t0 = std::max(a.front().t_s, b.front().t_s);
  const double t1 = std::min(a.back().t_s, b.back().t_s);
  if (t1 < t0) throw std::invalid_argument("the two paths do not overlap in time");
  // Every point time of either path inside the common span: between two of them both move
  // linearly, so the relative position is linear and its distance has one minimum.
  std::vector<double> times{t0, t1};
  for (const auto* p : {&a, &b})
    for (const auto& q : *p)
      if (q.t_s > t0 && q.t_s < t1) times.push_back(q.t_s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  const bool corridors = !a_half_width_m.empty() || !b_half_width_m.empty();
  const auto gap_at = [&](double t) {
    const TimedPoint pa = position_at(a, t), pb = position_at(b, t);
    const double d = std::hypot(pa.x_m - pb.x_m, pa.y_m - pb.y_m);
    if (!corridors) return d;
    return std::max(0.0, d - value_at(a, a_half_width_m, t) - value_at(b, b_half_width_m, t));
  };
  Approach best{gap_at(times.front()), times.front()};
  const auto consider = [&](double t) {
    const double g = gap_at(t);
    if (g < best.distance_m) best = {g, t};
  };
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double ta = times[i - 1], tb = times[i];
    consider(tb);
    const TimedPoint a0 = position_at(a, ta), a1 = position_at(a, tb);
    const TimedPoint b0 = position_at(b, ta), b1 = position_at(b, tb);
    const double rx = a0.x_m - b0.x_m, ry = a0.y_m - b0.y_m;
    const double vx = (a1.x_m - b1.x_m) - rx, vy = (a1.y_m - b1.y_m) - ry;  // per interval
    const double vv = vx * vx + vy * vy;
    if (vv <= 0.0) continue;
    const double w = -(rx * vx + ry * vy) / vv;
    if (w > 0.0 && w < 1.0) consider(ta + w * (tb - ta));
  }
  return best;
}

}  // namespace avk::kinematics
