#include "kinematics/approach_risk.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace avk::kinematics {

namespace {

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

// P(|m + z| < d) for z ~ N(0, var): the miss inside the standoff.
double inside_probability(double miss_m, double var_m2, double standoff_m) {
  if (!(var_m2 > 1e-12)) return miss_m < standoff_m ? 1.0 : 0.0;
  const double s = std::sqrt(var_m2);
  return std::clamp(normal_cdf((standoff_m - miss_m) / s) - normal_cdf((-standoff_m - miss_m) / s),
                    0.0, 1.0);
}

Covariance2 sum(const Covariance2& a, const Covariance2& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

double largest_eigenvalue(const Covariance2& c) {
  const double tr = c[0] + c[2], det = c[0] * c[2] - c[1] * c[1];
  return tr / 2.0 + std::sqrt(std::max(0.0, tr * tr / 4.0 - det));
}

}  // namespace

Covariance2 contact_covariance(const Contact& c, double t_s) {
  const double p2 = c.position_sd_m * c.position_sd_m;
  const double along = c.speed_sd_mps * t_s;
  const double across = c.speed_mps * c.course_sd_deg * std::numbers::pi / 180.0 * t_s;
  const double va = along * along, vc = across * across;
  const Point u = rotate_by_heading({0.0, 1.0}, c.course_deg);
  const Point n{u.y_m, -u.x_m};
  return {p2 + va * u.x_m * u.x_m + vc * n.x_m * n.x_m, va * u.x_m * u.y_m + vc * n.x_m * n.y_m,
          p2 + va * u.y_m * u.y_m + vc * n.y_m * n.y_m};
}

double approach_risk(const TimedPath& own, const std::vector<Covariance2>& own_covariance,
                     const Contact& contact, double standoff_m) {
  if (own.empty()) throw std::invalid_argument("a risk needs a path");
  if (own_covariance.size() != own.size())
    throw std::invalid_argument("one band covariance per path point");
  const Point v = rotate_by_heading({0.0, contact.speed_mps}, contact.course_deg);
  const bool contact_exact =
      contact.position_sd_m == 0.0 && contact.course_sd_deg == 0.0 && contact.speed_sd_mps == 0.0;
  double best = 0.0;
  // The risk at one moment: own position p with band c at time t.
  const auto at = [&](double t, double px, double py, const Covariance2& c) {
    const double rx = px - (contact.x_m + v.x_m * t), ry = py - (contact.y_m + v.y_m * t);
    const double m = std::hypot(rx, ry);
    const Covariance2 total = contact_exact ? c : sum(c, contact_covariance(contact, t));
    // Far outside any plausible spread the probability is nil: skip the error functions.
    const double reach = m - standoff_m;
    const double bound = total[0] + total[2];
    if (reach > 0.0 && reach * reach > 49.0 * bound) return;
    const double var =
        m > 1e-9 ? variance_along(total, {rx / m, ry / m}) : largest_eigenvalue(total);
    best = std::max(best, inside_probability(m, var, standoff_m));
  };
  at(own.front().t_s, own.front().x_m, own.front().y_m, own_covariance.front());
  for (std::size_t i = 1; i < own.size(); ++i) {
    const TimedPoint& a = own[i - 1];
    const TimedPoint& b = own[i];
    const double dt = b.t_s - a.t_s;
    if (!(dt > 0.0)) continue;
    // The segment's closest approach: the relative position is linear in time on it.
    const double rx = a.x_m - (contact.x_m + v.x_m * a.t_s),
                 ry = a.y_m - (contact.y_m + v.y_m * a.t_s);
    const double dx = (b.x_m - a.x_m) - v.x_m * dt, dy = (b.y_m - a.y_m) - v.y_m * dt;
    const double dd = dx * dx + dy * dy;
    const double w = dd > 0.0 ? std::clamp(-(rx * dx + ry * dy) / dd, 0.0, 1.0) : 0.0;
    const Covariance2& ca = own_covariance[i - 1];
    const Covariance2& cb = own_covariance[i];
    const Covariance2 c{ca[0] + w * (cb[0] - ca[0]), ca[1] + w * (cb[1] - ca[1]),
                        ca[2] + w * (cb[2] - ca[2])};
    at(a.t_s + w * dt, a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m), c);
    if (best >= 1.0) break;
  }
  return best;
}

}  // namespace avk::kinematics
